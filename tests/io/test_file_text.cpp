// Compressed data files (io/file_text.hpp): a .csv.gz reads as the .csv it
// holds, several gzip members one after the other, and a .gz that is not
// gzip, is cut short or corrupt is refused naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/file_text.hpp"
#include "io/input_error.hpp"
#include "io/measurement_csv.hpp"
#include "support/gzip_file.hpp"
#include "support/input_errors.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

namespace fs = std::filesystem;

const std::string kCsv =
    "# sample_rate_hz: 500\n"
    "t,F1,F2,F3,alpha1,beta1,alpha2,beta2,alpha3,beta3\n"
    "0,1000.5,2000.25,3000.125,0.01,-0.02,0.03,-0.04,0.05,-0.06\n"
    "0.002,1001.5,2001.25,3001.125,0.011,-0.021,0.031,-0.041,0.051,-0.061\n"
    "0.004,1002.5,2002.25,3002.125,0.012,-0.022,0.032,-0.042,0.052,-0.062\n"
    "0.006,1003.5,2003.25,3003.125,0.013,-0.023,0.033,-0.043,0.053,-0.063\n";

// The error of reading `file`; fails the test if there is none.
io::InputError error_reading(const fs::path& file) {
  return test::input_error_of([&] { io::read_record_csv(file); }, file.string());
}

TEST(CompressedFiles, ACsvGzReadsAsTheCsvItHolds) {
  test::TempDir dir("rigflex-gzip");
  test::write_text(dir.path() / "h1.csv", kCsv);
  test::write_gzip(dir.path() / "h1.csv.gz", kCsv);
  EXPECT_EQ(io::read_file_text(dir.path() / "h1.csv.gz"), kCsv);
  const rig::Record plain = io::read_record_csv(dir.path() / "h1.csv");
  const rig::Record packed = io::read_record_csv(dir.path() / "h1.csv.gz");
  EXPECT_EQ(packed.t, plain.t);
  EXPECT_EQ(packed.force, plain.force);
  EXPECT_EQ(packed.alpha, plain.alpha);
  EXPECT_EQ(packed.beta, plain.beta);
  EXPECT_EQ(packed.provenance.first_sample_line, plain.provenance.first_sample_line);
  EXPECT_EQ(packed.provenance.file, (dir.path() / "h1.csv.gz").string());
  // The extension's case does not matter.
  test::write_gzip(dir.path() / "H2.CSV.GZ", kCsv);
  EXPECT_EQ(io::read_record_csv(dir.path() / "H2.CSV.GZ").force, plain.force);
}

TEST(CompressedFiles, MembersOneAfterTheOtherReadAsOneText) {
  test::TempDir dir("rigflex-gzip");
  const size_t half = kCsv.find("0.004");
  test::write_gzip(dir.path() / "h.csv.gz", kCsv.substr(0, half));
  test::write_gzip(dir.path() / "h.csv.gz", kCsv.substr(half), "ab");  // appends a second member, as `cat a.gz b.gz`
  EXPECT_EQ(io::read_file_text(dir.path() / "h.csv.gz"), kCsv);
}

TEST(CompressedFiles, NotGzipTruncatedOrCorruptIsNamed) {
  test::TempDir dir("rigflex-gzip");
  const fs::path plain = dir.path() / "plain.csv.gz";
  test::write_text(plain, kCsv);
  io::InputError e = error_reading(plain);
  EXPECT_EQ(e.file(), plain.string());
  EXPECT_NE(std::string(e.what()).find("not a gzip file"), std::string::npos) << e.what();

  test::write_gzip(dir.path() / "whole.csv.gz", kCsv);
  const std::string bytes = test::read_text(dir.path() / "whole.csv.gz");
  const fs::path cut = dir.path() / "cut.csv.gz";
  test::write_text(cut, bytes.substr(0, bytes.size() / 2));
  e = error_reading(cut);
  EXPECT_EQ(e.file(), cut.string());
  EXPECT_NE(std::string(e.what()).find("end too early"), std::string::npos) << e.what();

  // Bytes in the middle of the deflate data changed: either the data or
  // the CRC check fails, never a silently different record.
  std::string bad = bytes;
  for (size_t i = 12; i < bad.size() - 8; i += 3) bad[i] = static_cast<char>(bad[i] ^ 0x5a);
  const fs::path corrupt = dir.path() / "corrupt.csv.gz";
  test::write_text(corrupt, bad);
  e = error_reading(corrupt);
  EXPECT_EQ(e.file(), corrupt.string());
  EXPECT_NE(std::string(e.what()).find("compressed data"), std::string::npos) << e.what();
}

TEST(CompressedFiles, AFolderMixesCsvAndCsvGzInNaturalOrder) {
  test::TempDir dir("rigflex-gzip");
  test::write_text(dir.path() / "h1.csv", kCsv);
  test::write_gzip(dir.path() / "h2.csv.gz", kCsv);
  test::write_text(dir.path() / "h10.csv", kCsv);
  test::write_text(dir.path() / "notes.gz", "not a measurement");
  const io::MeasurementSet set = io::read_measurement_set(dir.path());
  ASSERT_EQ(set.files.size(), 3u);
  EXPECT_EQ(set.files[0].filename(), "h1.csv");
  EXPECT_EQ(set.files[1].filename(), "h2.csv.gz");
  EXPECT_EQ(set.files[2].filename(), "h10.csv");
  EXPECT_EQ(set.records[1].force, set.records[0].force);
}

}  // namespace
}  // namespace rigflex
