// The mass-properties record reader (tares, static references) and the
// measurement-set layouts `rigflex identify` takes.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "report/identification_report.hpp"
#include "io/input_error.hpp"
#include "io/mass_record.hpp"
#include "io/measurement_csv.hpp"
#include "rig/rig_model.hpp"
#include "support/temp_files.hpp"

namespace {

using namespace rigflex;
using rigflex::test::TempDir;
using rigflex::test::write_text;

TEST(MassRecord, ReadsTheSpecRecordAndAnIdentificationMean) {
  const fe::MassProperties p = io::parse_mass_record(
      "mass: 2914.0\ncog: [0.511, -0.008, -0.598]\ninertia: [1632, 5729, 5510, 44, -483, 4]\n", "ref.yaml");
  EXPECT_EQ(p.mass, 2914.0);
  EXPECT_EQ(p.cog.z(), -0.598);
  // Negative-integral products sit off the diagonal as given.
  EXPECT_EQ(p.inertia(0, 1), 44.0);
  EXPECT_EQ(p.inertia(0, 2), -483.0);
  EXPECT_EQ(p.inertia(1, 2), 4.0);
  const fe::MassProperties j = io::parse_mass_record(
      R"({"rig": "x", "mean": {"mass": 10, "cog": [0, 0, -0.1], "inertia": [1, 2, 3, 0, 0, 0],
          "std": {"mass": 0, "cog": [0, 0, 0], "inertia": [0, 0, 0, 0, 0, 0]}}})",
      "identification.json");
  EXPECT_EQ(j.mass, 10.0);
  EXPECT_EQ(j.inertia(2, 2), 3.0);
}

TEST(MassRecord, BadRecordsNameFileLineAndKey) {
  struct Case {
    std::string text, key;
    int line;
  };
  const Case cases[] = {
      {"mass: 10\ncog: [0, 0]\ninertia: [1, 2, 3, 0, 0, 0]\n", "cog", 2},
      {"mass: -1\ncog: [0, 0, 0]\ninertia: [1, 2, 3, 0, 0, 0]\n", "mass", 1},
      {"mass: 10\ncog: [0, 0, 0]\ninertia: [1, 2, 3, 0, 0]\n", "inertia", 3},
      {"mass: 10\ncog: [0, 0, 0]\ninertia: [1, 2, 3, 0, 0, 0]\ncentre: [0, 0, 0]\n", "centre", 4},
      {"cog: [0, 0, 0]\ninertia: [1, 2, 3, 0, 0, 0]\n", "mass", 1},
  };
  for (const auto& c : cases) {
    try {
      io::parse_mass_record(c.text, "tare.yaml");
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const io::InputError& e) {
      EXPECT_EQ(e.file(), "tare.yaml");
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_EQ(e.line(), c.line) << e.what();
    }
  }
}

TEST(MassRecord, JsonOfTheRecordReadsBack) {
  fe::MassProperties p;
  p.mass = 300;
  p.cog = Eigen::Vector3d(0.04, -0.02, -0.15);
  p.inertia = rig::inertia_tensor({15, 20, 18, 0.5, -1, 0.3});
  const fe::MassProperties q = io::parse_mass_record(io::mass_record_json(p).dump(), "x.json");
  EXPECT_EQ(q.mass, p.mass);
  EXPECT_EQ(q.cog, p.cog);
  EXPECT_EQ(q.inertia, p.inertia);
}

TEST(MassRecord, ReadsTheMeanOfWhatIdentifyWrites) {
  // --tare and --reference take identify's own output: its `mean` carries
  // std, the 95 % interval and principal axes besides the record.
  report::IdentificationReport rep;
  rep.rig = "r";
  rep.set_names = {"set1", "set2"};
  rep.set_files = {{"a.csv"}, {"b.csv"}};
  std::vector<identify::IdentificationResult> results(2);
  for (int k = 0; k < 2; ++k) {
    results[k].observable = true;
    results[k].properties.mass = 400;
    results[k].properties.cog = Eigen::Vector3d(0.01 * k, 0.0, -0.1);
    results[k].properties.inertia = rig::inertia_tensor({300.0 + k, 420, 650, 1, 0, 0});
  }
  rep.add(identify::IdentificationAlgorithm::rigid, results);
  const nlohmann::ordered_json j = rep.json();
  ASSERT_TRUE(j["mean"].contains("confidence_interval_95"));
  const fe::MassProperties p = io::parse_mass_record(j.dump(2), "identification.json");
  EXPECT_EQ(p.mass, 400.0);
  EXPECT_NEAR(p.cog.x(), 0.005, 1e-15);
  EXPECT_NEAR(p.inertia(0, 0), 300.5, 1e-12);
  EXPECT_EQ(p.inertia(0, 1), 1.0);
}

// A minimal valid history of `rods` rods.
std::string history(int rods) {
  std::string header = "t", row = "0", row2 = "0.002";
  for (int i = 1; i <= rods; ++i) header += ",F" + std::to_string(i), row += ",100", row2 += ",100";
  for (int i = 1; i <= rods; ++i) {
    header += ",alpha" + std::to_string(i) + ",beta" + std::to_string(i);
    row += ",0,0";
    row2 += ",0,0";
  }
  return header + "\n" + row + "\n" + row2 + "\n";
}

TEST(MeasurementSets, FolderOfSetsFilesAndSetFolders) {
  const TempDir dir("rigflex-sets");
  for (const char* set : {"set10", "set2", "set1"}) {
    std::filesystem::create_directories(dir.path() / "meas" / set);
    for (const char* h : {"h1.csv", "h2.csv"}) write_text(dir.path() / "meas" / set / h, history(3));
  }
  std::filesystem::create_directories(dir.path() / "meas" / ".hidden");
  write_text(dir.path() / "meas" / ".hidden" / "h1.csv", history(3));
  write_text(dir.path() / "loose1.csv", history(3));
  write_text(dir.path() / "loose2.csv", history(3));

  const io::MeasurementSets a = io::read_measurement_sets({dir.path() / "meas"}, 3);
  ASSERT_EQ(a.sets.size(), 3u);  // natural order, hidden folder skipped
  EXPECT_EQ(std::filesystem::path(a.names[0]).filename(), "set1");
  EXPECT_EQ(std::filesystem::path(a.names[1]).filename(), "set2");
  EXPECT_EQ(std::filesystem::path(a.names[2]).filename(), "set10");
  EXPECT_EQ(a.sets[2].records.size(), 2u);
  EXPECT_EQ(a.sets[0].records[0].provenance.first_sample_line, 2);  // header on line 1

  const io::MeasurementSets b =
      io::read_measurement_sets({dir.path() / "meas" / "set2", dir.path() / "loose1.csv", dir.path() / "loose2.csv"}, 3);
  ASSERT_EQ(b.sets.size(), 2u);
  EXPECT_EQ(b.names[1], "files");
  EXPECT_EQ(b.sets[1].records.size(), 2u);
}

TEST(MeasurementSets, MissingPathsEmptyFoldersAndRodCountsAreNamed) {
  const TempDir dir("rigflex-sets");
  std::filesystem::create_directories(dir.path() / "empty" / "sub");
  EXPECT_THROW(io::read_measurement_sets({dir.path() / "nothing"}, 3), io::InputError);
  try {
    io::read_measurement_sets({dir.path() / "empty"}, 3);
    ADD_FAILURE();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "empty").string());
  }
  write_text(dir.path() / "four.csv", history(4));
  try {
    io::read_measurement_sets({dir.path() / "four.csv"}, 3);
    ADD_FAILURE();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "four.csv").string());
    EXPECT_EQ(e.line(), 1);
  }
}

}  // namespace
