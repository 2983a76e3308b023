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
#include "rig/record.hpp"

namespace rigflex::io {

// Reads one time history into a record: its comments (the leading
// "# key: value" lines, in order), the file and the line of its first sample
// as its provenance. expected_rods = 0 infers n from the columns present
// (F1..Fn contiguous, with alpha1..alphan and beta1..betan); otherwise a file
// with another rod count is refused. Bad input throws InputError naming the
// file, the 1-based line and the column.
rig::Record read_record_csv(const std::filesystem::path& file, int expected_rods = 0);
// The same from a stream; `file_name` names the text in errors and in the provenance.
rig::Record parse_record_csv(std::istream& in, const std::string& file_name, int expected_rods = 0);

// The file's text: the provenance's comments, header "t,F1..Fn,alpha1,beta1,..,alphan,betan",
// one line per sample, numbers as the shortest decimal that reads back as the
// same double, LF line endings. Deterministic. Throws std::invalid_argument
// for a history that could not be read back as itself (inconsistent sizes, no
// samples, non-finite values, time not strictly increasing, comments that do
// not fit on a "# key: value" line).
std::string format_record_csv(const rig::Record& h);
// Checks and formats `h` first, then writes the file atomically: on any error
// no file (and no temporary file) is left, and an existing file is unchanged.
void write_record_csv(const std::filesystem::path& file, const rig::Record& h);

// The InputError for a RecordError raised on records[e.history()] (by
// identification, compare or diagnose): the record's file, the line of the
// sample (its provenance), the channel and the reason. A record that was not
// read from a file, or an unknown history, is named "(a measurement)". The
// one place where a record's problem becomes file:line.
InputError record_input_error(const std::vector<rig::Record>& records, const rig::RecordError& e);

// One measurement of a body: the time histories of a folder.
struct MeasurementSet {
  std::vector<std::filesystem::path> files;
  std::vector<rig::Record> records;  // records[i] read from files[i] (its provenance names it too)
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
