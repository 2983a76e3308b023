#pragma once
// What compare and diagnose share: the rig model with any added effects
// files and the measured records of every set, each carrying the file it was
// read from (its provenance), which turns a record error back into the
// file and line.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rig/record.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::app {

struct MeasuredModel {
  rig::RigModel model;
  std::vector<std::filesystem::path> model_files;  // rig file, then the effects files
  std::string label;                               // "rig.yaml + effects/air_drag.yaml"
  std::vector<std::string> effect_names;
  std::vector<rig::Record> records;                // every history of every set, in order
  std::vector<const rig::Record*> pointers() const;
  std::vector<std::string> sources() const;        // each record's file
};

MeasuredModel read_measured_model(const std::string& rig_file, const std::vector<std::string>& effects_files,
                                  const std::vector<std::string>& data, bool quiet, const char* command);

// Runs a command's work on mm: an integrator failure during it becomes the
// InputError that names mm's rig and effects files (io::integration_error).
int run_on_measured_model(const MeasuredModel& mm, const std::function<int()>& work);

// The readers' warnings (a clipped or stuck channel) on stderr, one line each
// ("rigflex: warning: FILE: line N: ..."), even with --quiet: they are about
// the data, not progress.
void print_record_warnings(const std::vector<rig::Record>& records);

// The InputError for a record error of one of mm's records (its file and line).
[[noreturn]] void rethrow_record_error(const MeasuredModel& mm, const rig::RecordError& e);

}  // namespace rigflex::app
