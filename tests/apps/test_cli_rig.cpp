// `rigflex check` and `rigflex simulate` end to end on a small rig: the files
// they write (check.json; measurement CSVs per shared/spec/rig-conventions.md),
// reproducibility by seed, and bad input (file:line:key, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli_support.hpp"
#include "io/measurement_csv.hpp"
#include "support/temp_files.hpp"
#include "support/text_edits.hpp"

namespace {

using namespace rigflex::test;

// Three vertical rigid rods of L = 1 m at R = 0.4 m around P, 100 kg body with
// Jzz = 12 kg m^2, g = 9.81: swing at sqrt(g/L)/2pi twice, yaw at
// sqrt(m g R^2 / (Jzz L))/2pi. No frames, no effects (no in-process reduction).
const std::string kSmallRig = R"(name: small-rig
geometry:
  gravity: 9.81
  reference_point: [0, 0, 0]
  rods:
    - {upper: [0.4, 0.0, 1.0], lower: [0.4, 0.0, 0.0], length: 1.0, encoder_axis: [1, 0, 0]}
    - {upper: [-0.2, 0.3464, 1.0], lower: [-0.2, 0.3464, 0.0], length: 1.0, encoder_axis: [1, 0, 0]}
    - {upper: [-0.2, -0.3464, 1.0], lower: [-0.2, -0.3464, 0.0], length: 1.0, encoder_axis: [0, 1, 0]}
body:
  mass: 100.0
  cog: [0, 0, -0.1]
  inertia: [6.25, 6.25, 12.0, 0, 0, 0]
sensors:
  sample_rate: 250
  load_cell: {noise: 0.5}
  encoder: {bits: 17}
)";

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// A rig file in its own folder.
struct RigFile {
  TempDir dir{"rigflex-cli-rig"};
  fs::path file;
  explicit RigFile(const std::string& text, const std::string& name = "rig.yaml") : file(dir.path() / name) {
    write_text(file, text);
  }
};

// The file's lines after its '#' comments and header: the samples.
std::string samples_of(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, out;
  bool header = false;
  while (std::getline(in, line)) {
    if (!header) {
      header = !line.starts_with("#");
      continue;
    }
    out += line + "\n";
  }
  return out;
}

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// ------------------------------------------------------------------ check

TEST(CliRig, CheckOfARigidRigWritesCheckJson) {
  const RigFile rig(kSmallRig);
  const fs::path out = rig.dir.path() / "out";
  const CliRun r = run("check " + rig.file.string() + " --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("no deformation mode"), std::string::npos) << r.out;
  std::ifstream in(out / "check.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["rig"], "small-rig");
  // Rigid rods are 300 Hz springs in the model: they stretch by g/(2 pi 300)^2
  // = 2.8e-6 m, which moves the swing by 1.4e-6 relative; 1e-4 allowed.
  const double swing = std::sqrt(9.81 / 1.0) / kTwoPi;
  const double yaw = std::sqrt(100.0 * 9.81 * 0.4 * 0.4 / (12.0 * 1.0)) / kTwoPi;
  ASSERT_EQ(j["swing_frequencies_hz"].size(), 3u);
  EXPECT_NEAR(j["swing_frequencies_hz"][0].get<double>(), swing, 1e-4 * swing);
  EXPECT_NEAR(j["swing_frequencies_hz"][1].get<double>(), swing, 1e-4 * swing);
  EXPECT_NEAR(j["swing_frequencies_hz"][2].get<double>(), yaw, 1e-4 * yaw);
  // Nothing deforms: no f1, no ratio, and the rigid algorithm is safe.
  ASSERT_TRUE(j.contains("first_deformation_frequency_hz"));
  EXPECT_TRUE(j["first_deformation_frequency_hz"].is_null()) << j["first_deformation_frequency_hz"];
  ASSERT_TRUE(j.contains("ratio"));
  EXPECT_TRUE(j["ratio"].is_null()) << j["ratio"];
  EXPECT_EQ(j["verdict"], "rigid identification safe");
  EXPECT_TRUE(fs::exists(out / "rig_modes.pvd"));
  for (const auto& f : files_under(out)) EXPECT_EQ(f.string().find(".tmp"), std::string::npos) << f;
}

TEST(CliRig, CheckOfCompliantRodsGivesTheBounceAsF1) {
  // Rods of k = 1e5 N/m: the body bounces at sqrt(3 k / m)/2pi = 8.717 Hz, the
  // first deformation mode (rolls are at 9.9 Hz). Tolerance 1e-6 relative
  // (the rods' geometric stiffness does not act along them).
  const RigFile rig(kSmallRig + "effects:\n  rod_compliance: {stiffness: 1.0e5}\n");
  const fs::path out = rig.dir.path() / "out";
  const CliRun r = run("check " + rig.file.string() + " --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(out / "check.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const double bounce = std::sqrt(3 * 1.0e5 / 100.0) / kTwoPi;
  ASSERT_TRUE(j["first_deformation_frequency_hz"].is_number()) << j["first_deformation_frequency_hz"];
  const double f1 = j["first_deformation_frequency_hz"].get<double>();
  EXPECT_NEAR(f1, bounce, 1e-6 * bounce);
  double highest = 0;
  for (const auto& f : j["swing_frequencies_hz"]) highest = std::max(highest, f.get<double>());
  EXPECT_NEAR(j["ratio"].get<double>(), f1 / highest, 1e-12 * f1 / highest);
  EXPECT_GT(j["ratio"].get<double>(), 4.0);
  EXPECT_EQ(j["verdict"], "rigid identification safe");
}

TEST(CliRig, CheckOfABadRigNamesFileLineAndKeyAndWritesNothing) {
  const std::string text = replace_first(kSmallRig, "mass: 100.0", "mass: -100.0");
  const RigFile rig(text);
  const fs::path out = rig.dir.path() / "out";
  const CliRun r = run("check " + rig.file.string() + " --quiet --out " + out.string());
  EXPECT_EQ(r.code, 2) << r.out;
  const std::string where = rig.file.string() + ":" + std::to_string(line_of(text, "mass: -100.0")) + ": key 'body.mass'";
  EXPECT_NE(r.out.find(where), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliRig, CheckWithoutStaticEquilibriumNamesTheEffect) {
  // Upper joints of 1 m/N would let 100 kg sink 327 m: no equilibrium is
  // found near the rig. (Rods that soft are refused by their range: a
  // frame's joint compliance has no upper bound.)
  const std::string text = kSmallRig +
                           "effects:\n  fixed_frame_flexibility: {joint_compliance: {joints: [[0, 0, 1.0], [0, 0, "
                           "1.0], [0, 0, 1.0]]}}\n";
  const RigFile rig(text);
  const fs::path out = rig.dir.path() / "out";
  const CliRun r = run("check " + rig.file.string() + " --quiet --out " + out.string());
  EXPECT_EQ(r.code, 2) << r.out;
  const std::string where = rig.file.string() + ":" + std::to_string(line_of(text, "fixed_frame_flexibility")) +
                            ": key 'effects.fixed_frame_flexibility'";
  EXPECT_NE(r.out.find(where), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no static equilibrium found"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

// --------------------------------------------------------------- simulate

TEST(CliRig, SimulateWritesMeasurementFilesOfTheSpec) {
  const RigFile rig(kSmallRig);
  const fs::path out = rig.dir.path() / "meas";
  const CliRun r = run("simulate " + rig.file.string() +
                       " --sets 1 --histories 2 --duration 2 --seed 3 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  // The records, and the manifest of what this run wrote (docs/reliability.md).
  EXPECT_EQ(files_under(out), (std::vector<fs::path>{".rigflex-manifest-simulate", "set1/h1.csv", "set1/h2.csv"}));
  for (const char* name : {"h1.csv", "h2.csv"}) {
    SCOPED_TRACE(name);
    const fs::path file = out / "set1" / name;
    const std::string text = read_text(file);
    // Leading "# key: value" comments, then the header of the spec's columns.
    std::istringstream in(text);
    std::string line;
    int comments = 0;
    while (std::getline(in, line) && line.starts_with("#")) {
      ++comments;
      EXPECT_TRUE(line.starts_with("# ") && line.find(": ") != std::string::npos) << line;
    }
    EXPECT_GT(comments, 0);
    EXPECT_EQ(line, "t,F1,F2,F3,alpha1,beta1,alpha2,beta2,alpha3,beta3");
    EXPECT_EQ(text.find('\r'), std::string::npos);
    // The spec-strict reader takes it for a 3-rod rig.
    const rigflex::rig::Record h = rigflex::io::read_record_csv(file, 3);
    EXPECT_EQ(h.comment("rig"), "small-rig");
    EXPECT_EQ(h.comment("sample_rate_hz"), "250");
    EXPECT_EQ(h.comment("seed"), "3");
    // 2 s at 250 Hz from t = 0: 501 samples, 4 ms apart (to 1e-12 s).
    ASSERT_EQ(h.samples(), 501);
    EXPECT_EQ(h.t(0), 0.0);
    for (int i = 1; i < h.samples(); ++i) ASSERT_NEAR(h.t(i) - h.t(i - 1), 0.004, 1e-12) << i;
    // Three rods carry the weight: the tensions' sum stays within 2 % of m g
    // (pushes of at most 0.45 m/s^2 leave swings of a few cm, whose
    // centripetal and vertical loads are under 1 %; noise 0.5 N).
    for (int i = 0; i < h.samples(); i += 50) {
      EXPECT_NEAR(h.force.row(i).sum(), 100.0 * 9.81, 0.02 * 100.0 * 9.81) << "t = " << h.t(i);
    }
  }
  // The two histories have different pushes.
  EXPECT_NE(samples_of(read_text(out / "set1/h1.csv")), samples_of(read_text(out / "set1/h2.csv")));
}

TEST(CliRig, SimulateIsReproducibleBySeed) {
  const RigFile rig(kSmallRig);
  auto simulate = [&](const std::string& seed, const std::string& folder) {
    const fs::path out = rig.dir.path() / folder;
    const CliRun r = run("simulate " + rig.file.string() + " --sets 1 --histories 2 --duration 2 --seed " + seed +
                         " --quiet --out " + out.string());
    EXPECT_EQ(r.code, 0) << r.out;
    return std::vector<std::string>{read_text(out / "set1/h1.csv"), read_text(out / "set1/h2.csv")};
  };
  const auto a = simulate("3", "a");
  const auto b = simulate("3", "b");
  const auto c = simulate("4", "c");
  for (size_t k = 0; k < 2; ++k) {
    ASSERT_FALSE(a[k].empty());
    EXPECT_EQ(a[k], b[k]) << "h" << k + 1 << ".csv differs between two runs with seed 3";
    // Not only the "# seed:" comment: the samples themselves differ.
    EXPECT_NE(samples_of(a[k]), samples_of(c[k])) << "h" << k + 1 << ".csv: seed 4 gave the samples of seed 3";
  }
}

TEST(CliRig, SimulateRefusesZeroHistories) {
  const RigFile rig(kSmallRig);
  const fs::path out = rig.dir.path() / "meas";
  const CliRun r = run("simulate " + rig.file.string() + " --histories 0 --quiet --out " + out.string());
  EXPECT_NE(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("--histories: must be positive, got 0"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliRig, SimulateOfARigWhoseNameCannotGoInTheFiles) {
  // Refused when read, not when the CSV writer meets the "# rig:" line.
  const std::string text = replace_first(kSmallRig, "name: small-rig", "name: \"small-rig \"");
  const RigFile rig(text);
  const fs::path out = rig.dir.path() / "meas";
  const CliRun r = run("simulate " + rig.file.string() + " --histories 1 --duration 1 --quiet --out " + out.string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find(rig.file.string() + ":1: key 'name'"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
