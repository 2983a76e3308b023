#pragma once
// Measurement files: one time history of the rig per CSV file, as the data
// contract (shared/spec/rig-conventions.md, "Measurement files") defines them.
// Real rig logs arrive in this form, so the reader takes exactly what the
// contract allows and names the file, line and column of anything else; the
// writer produces files that read back bit for bit. See
// docs/measurement-files.md.
#include <Eigen/Dense>

#include <filesystem>
#include <istream>
#include <string>
#include <utility>
#include <vector>

#include "io/input_error.hpp"
#include "rig/simulation.hpp"

namespace rigflex::io {

struct TimeHistory {
  std::vector<std::pair<std::string, std::string>> comments;  // leading "# key: value" lines, in order
  Eigen::VectorXd t;      // s, strictly increasing
  Eigen::MatrixXd force;  // samples x n, columns F1..Fn (N, tension positive)
  Eigen::MatrixXd alpha;  // samples x n, alpha1..alphan (rad)
  Eigen::MatrixXd beta;   // samples x n, beta1..betan (rad)
  int header_line = 0;    // 1-based line of the header in the file read (sample k is on line header_line + 1 + k)

  int rods() const;     // n
  int samples() const;  // rows of t
  // The value of the first comment with this key; "" if there is none.
  std::string comment(const std::string& key) const;
};

// Reads one time history. expected_rods = 0 infers n from the columns present
// (F1..Fn contiguous, with alpha1..alphan and beta1..betan); otherwise a file
// with another rod count is refused. Bad input throws InputError naming the
// file, the 1-based line and the column.
TimeHistory read_time_history(const std::filesystem::path& file, int expected_rods = 0);
// The same from a stream; `file_name` is only used in errors.
TimeHistory parse_time_history(std::istream& in, const std::string& file_name, int expected_rods = 0);

// The file's text: comments, header "t,F1..Fn,alpha1,beta1,..,alphan,betan",
// one line per sample, numbers as the shortest decimal that reads back as the
// same double, LF line endings. Deterministic. Throws std::invalid_argument
// for a history that could not be read back as itself (inconsistent sizes, no
// samples, non-finite values, time not strictly increasing, comments that do
// not fit on a "# key: value" line).
std::string format_time_history(const TimeHistory& h);
// Checks and formats `h` first, then writes the file atomically: on any error
// no file (and no temporary file) is left, and an existing file is unchanged.
void write_time_history(const std::filesystem::path& file, const TimeHistory& h);

// The same samples as the rig library's record (comments stay with the file).
rig::VirtualHistory to_record(const TimeHistory& h);
TimeHistory to_time_history(const rig::VirtualHistory& r);

// One measurement of a body: the time histories of a folder.
struct MeasurementSet {
  std::vector<std::filesystem::path> files;
  std::vector<TimeHistory> histories;  // histories[i] read from files[i]
};

// All *.csv files directly in `folder` (extension case-insensitive, hidden
// files skipped), in natural order (h2 before h10); at least one. Each is read
// with expected_rods, and all must have the rod count of the first.
MeasurementSet read_measurement_set(const std::filesystem::path& folder, int expected_rods = 0);

// The sets that paths name, as `rigflex identify` takes them: a folder with
// .csv files is one set; a folder without any holds one set per subfolder
// (natural order, hidden ones skipped); files given directly form one set
// together. `names[i]` names set i (its folder, or "files").
struct MeasurementSets {
  std::vector<std::string> names;
  std::vector<MeasurementSet> sets;
};
MeasurementSets read_measurement_sets(const std::vector<std::filesystem::path>& paths, int expected_rods = 0);

}  // namespace rigflex::io
