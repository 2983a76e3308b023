#include "apps/measured_model.hpp"

#include <cstdio>

#include "apps/work_estimate.hpp"
#include "io/input_error.hpp"
#include "io/integration_error.hpp"
#include "io/measurement_csv.hpp"
#include "io/rig_reader.hpp"

namespace rigflex::app {

std::vector<const rig::Record*> MeasuredModel::pointers() const {
  std::vector<const rig::Record*> p;
  for (const auto& r : records) p.push_back(&r);
  return p;
}

std::vector<std::string> MeasuredModel::sources() const {
  std::vector<std::string> s;
  for (const auto& r : records) s.push_back(r.provenance.file);
  return s;
}

MeasuredModel read_measured_model(const std::string& rig_file, const std::vector<std::string>& effects_files,
                                  const std::vector<std::string>& data, bool quiet, const char* command) {
  MeasuredModel mm;
  const io::RigReadOptions ro = frame_reduction_options(command, quiet);
  mm.model = io::resolve_rig(io::read_rig_spec(rig_file), ro);
  mm.model_files.push_back(rig_file);
  mm.label = std::filesystem::path(rig_file).filename().string();
  for (const auto& f : effects_files) {
    io::add_effects(mm.model, f, ro);
    mm.model_files.push_back(f);
    mm.label += " + " + std::filesystem::path(f).filename().string();
  }
  for (const auto& e : mm.model.effects) mm.effect_names.push_back(e->name());
  std::vector<std::filesystem::path> paths(data.begin(), data.end());
  io::MeasurementSets sets = io::read_measurement_sets(paths, mm.model.geometry.rod_count());
  for (auto& s : sets.sets) {
    for (auto& r : s.records) mm.records.push_back(std::move(r));
  }
  if (!quiet) std::fprintf(stderr, "%s: %zu histories read\n", command, mm.records.size());
  print_record_warnings(mm.records);
  return mm;
}

void print_record_warnings(const std::vector<rig::Record>& records) {
  for (const auto& r : records) {
    for (const auto& w : r.provenance.warnings) {
      std::fprintf(stderr, "rigflex: warning: %s: %s\n", r.provenance.file.c_str(), w.c_str());
    }
  }
}

void rethrow_record_error(const MeasuredModel& mm, const rig::RecordError& e) {
  throw io::record_input_error(mm.records, e);
}

int run_on_measured_model(const MeasuredModel& mm, const std::function<int()>& work) {
  try {
    return work();
  } catch (const rig::IntegrationFailure& e) {
    throw io::integration_error(e, mm.model, mm.model_files);
  }
}

}  // namespace rigflex::app
