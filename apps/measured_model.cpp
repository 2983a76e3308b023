#include "apps/measured_model.hpp"

#include <cstdio>

#include "io/input_error.hpp"
#include "io/rig_reader.hpp"

namespace rigflex::app {

std::vector<const rig::VirtualHistory*> MeasuredModel::pointers() const {
  std::vector<const rig::VirtualHistory*> p;
  for (const auto& r : records) p.push_back(&r);
  return p;
}

std::vector<std::string> MeasuredModel::sources() const {
  std::vector<std::string> s;
  for (const auto& f : files) s.push_back(f.string());
  return s;
}

MeasuredModel read_measured_model(const std::string& rig_file, const std::vector<std::string>& effects_files,
                                  const std::vector<std::string>& data, bool quiet, const char* command) {
  MeasuredModel mm;
  io::RigReadOptions ro;
  if (!quiet) {
    ro.progress = [command](const std::string& s) { std::fprintf(stderr, "%s: frame reduction: %s\n", command, s.c_str()); };
  }
  mm.model = io::read_rig(rig_file, ro);
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
    for (size_t i = 0; i < s.histories.size(); ++i) {
      mm.records.push_back(io::to_record(s.histories[i]));
      mm.histories.push_back(std::move(s.histories[i]));
      mm.files.push_back(s.files[i]);
    }
  }
  if (!quiet) std::fprintf(stderr, "%s: %zu histories read\n", command, mm.records.size());
  return mm;
}

void rethrow_record_error(const MeasuredModel& mm, const identify::RecordError& e) {
  if (e.history() < 0 || static_cast<size_t>(e.history()) >= mm.files.size()) {
    throw io::InputError("(a measurement)", 0, e.channel(), e.what());
  }
  const auto i = static_cast<size_t>(e.history());
  const io::TimeHistory& h = mm.histories[i];
  const int line = e.sample() >= 0 ? h.header_line + 1 + static_cast<int>(e.sample()) : 0;
  throw io::InputError(mm.files[i].string(), line, e.channel(), e.what());
}

}  // namespace rigflex::app
