#pragma once
// What compare and diagnose share: the rig model with any added effects
// files, the measured histories flattened over the sets, and the mapping of
// a record error back to its file and line.
#include <filesystem>
#include <string>
#include <vector>

#include "io/measurement_csv.hpp"
#include "identify/identification_kinematics.hpp"
#include "rig/rig_model.hpp"
#include "rig/simulation.hpp"

namespace rigflex::app {

struct MeasuredModel {
  rig::RigModel model;
  std::vector<std::filesystem::path> model_files;  // rig file, then the effects files
  std::string label;                               // "rig.yaml + effects/air_drag.yaml"
  std::vector<std::string> effect_names;
  std::vector<io::TimeHistory> histories;          // every history of every set
  std::vector<std::filesystem::path> files;        // histories[i] came from files[i]
  std::vector<rig::VirtualHistory> records;
  std::vector<const rig::VirtualHistory*> pointers() const;
  std::vector<std::string> sources() const;
};

MeasuredModel read_measured_model(const std::string& rig_file, const std::vector<std::string>& effects_files,
                                  const std::vector<std::string>& data, bool quiet, const char* command);

// The InputError for a record error of history `history` (its file and line).
[[noreturn]] void rethrow_record_error(const MeasuredModel& mm, const identify::RecordError& e);

}  // namespace rigflex::app
