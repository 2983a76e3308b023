#include "rig/effect_kinds.hpp"

#include <stdexcept>

#include "rig/effect_kind_entries.hpp"

namespace rigflex::rig {

const char* hook_name(EffectHook h) {
  switch (h) {
    case EffectHook::build: return "build";
    case EffectHook::add_loads: return "add_loads";
    case EffectHook::measure: return "measure";
  }
  return "";
}

const std::vector<EffectKind>& effect_kinds() {
  static const std::vector<EffectKind> kinds = {
      kinds::fixed_frame_flexibility(), kinds::carrying_frame_flexibility(), kinds::rod_compliance(),
      kinds::rod_mass(),                kinds::joint_friction(),             kinds::air_drag(),
      kinds::encoder_offset(),          kinds::rod_length_error(),           kinds::joint_position_error(),
      kinds::load_cell_gain()};
  return kinds;
}

const EffectKind* find_effect_kind(const std::string& name) {
  for (const auto& k : effect_kinds()) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

EffectParseContext parse_context(const RigModel& model, const std::string& name) {
  return parse_context(model.geometry, model.body.mass, name);
}

EffectParseContext parse_context(const RigGeometry& geometry, double body_mass, const std::string& name) {
  EffectParseContext x;
  x.key = "effects." + name;
  x.rods = geometry.rod_count();
  x.geometry = &geometry;
  x.body_mass = body_mass;
  x.read_frame = [key = x.key](bool) -> FrameSource {
    throw std::logic_error(key + ": a frame's files are read by the rig file's reader, not here");
  };
  return x;
}

const std::vector<const char*>& effect_names() {
  static const std::vector<const char*> names = [] {
    std::vector<const char*> out;
    for (const auto& k : effect_kinds()) out.push_back(k.name.c_str());
    return out;
  }();
  return names;
}

std::string effect_name_list() {
  std::string known;
  for (const auto& k : effect_kinds()) known += (known.empty() ? "" : ", ") + k.name;
  return known;
}

std::vector<std::string> allowed_keys(const EffectKind& kind) {
  std::vector<std::string> keys = {"enabled"};
  for (const auto& p : kind.parameters) keys.push_back(p.key);
  return keys;
}

}  // namespace rigflex::rig
