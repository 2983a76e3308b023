#include "io/rig_reader.hpp"

#include <algorithm>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "fe/error.hpp"
#include "io/model_reader.hpp"
#include "io/reduced_export.hpp"
#include "io/yaml_document.hpp"
#include "io/yaml_fields.hpp"
#include "io/yaml_parameters.hpp"
#include "reduction/frame_reduction.hpp"
#include "rig/effect.hpp"
#include "rig/effect_kinds.hpp"
#include "rig/effect_ranges.hpp"
#include "rig/frame_models.hpp"
#include "rig/rig_spec.hpp"

namespace rigflex::io {
namespace {

using rig::Vec3;

struct RigFileReader {
  YamlContext ctx;
  std::filesystem::path base;
  int rods = 0;
  double mass = 0;  // the body's, for the joints of a frame given by its joint compliance

  // Runs `read` with the keys of its errors named under `path`: "upper" read
  // for rod 2 is reported as "geometry.rods[2].upper". Errors about other
  // files (a frame model) and keys already under `path` pass unchanged.
  template <class F>
  auto within(const std::string& path, F read) const -> decltype(read()) {
    try {
      return read();
    } catch (const InputError& e) {
      const std::string& k = e.key();
      const bool named = k == path || k.rfind(path + ".", 0) == 0 || k.rfind(path + "[", 0) == 0;
      if (e.file() != ctx.file() || k.empty() || named) throw;
      throw InputError(e.file(), e.line(), path + "." + k, e.reason());
    }
  }

  rig::RigGeometry geometry(const YAML::Node& g) const {
    ctx.expect_map(g, "geometry", {"gravity", "reference_point", "rods"});
    rig::RigGeometry out;
    out.gravity = ctx.number_or(g, "gravity", 9.80665, ranges::gravity);
    out.reference_point = ctx.vec3(g, "reference_point", ranges::coordinate);
    const YAML::Node rods_node = ctx.required(g, "rods");
    ctx.expect_sequence(rods_node, "rods");
    for (const auto& r : rods_node) {
      // Rod i is entry i (1-based), as in the spec and RigModel::validate.
      within("geometry.rods[" + std::to_string(out.rods.size() + 1) + "]", [&] {
        ctx.expect_map(r, "rods[]", {"upper", "lower", "length", "encoder_axis"});
        rig::RodGeometry rod;
        rod.upper = ctx.vec3(r, "upper", ranges::coordinate);
        rod.lower = ctx.vec3(r, "lower", ranges::coordinate);
        rod.length = ctx.number(r, "length", ranges::length);
        rod.encoder_axis = ctx.vec3(r, "encoder_axis");
        out.rods.push_back(rod);
      });
    }
    return out;
  }

  rig::BodyUncertainty body_uncertainty(const YAML::Node& b) const {
    rig::BodyUncertainty u;
    const YAML::Node n = b["uncertainty"];
    if (!n) return u;
    within("body.uncertainty", [&] {
      ctx.expect_map(n, "uncertainty", {"cog", "inertia"});
      if (n["cog"]) u.cog = ctx.vec3(n, "cog");
      if (n["inertia"]) {
        const auto J = ctx.numbers(n, "inertia", 6);
        u.inertia = std::array<double, 6>{J[0], J[1], J[2], J[3], J[4], J[5]};
      }
    });
    return u;
  }

  fe::MassProperties body(const YAML::Node& b) const {
    ctx.expect_map(b, "body", {"mass", "cog", "inertia", "name", "uncertainty"});
    fe::MassProperties m;
    m.mass = ctx.number(b, "mass", ranges::mass);
    m.cog = ctx.vec3(b, "cog", ranges::coordinate);
    const auto J = ctx.numbers(b, "inertia", 6, ranges::inertia);
    m.inertia = rig::inertia_tensor({J[0], J[1], J[2], J[3], J[4], J[5]});
    return m;
  }

  // One value for every rod or a list of one per rod.
  std::vector<double> per_rod(const YAML::Node& map, const std::string& key) const {
    if (ctx.required(map, key).IsSequence()) return ctx.numbers(map, key, static_cast<size_t>(rods));
    return std::vector<double>(static_cast<size_t>(rods), ctx.number(map, key));
  }

  // `geometry`: the rods' lengths, for EA/L.
  rig::RodProperties rod_properties(const YAML::Node& n, const rig::RigGeometry& geometry) const {
    ctx.expect_map(n, "rods", {"stiffness", "youngs_modulus", "area", "damping", "uncertainty"});
    rig::RodProperties p;
    const bool by_material = n["youngs_modulus"] || n["area"];
    if (n["stiffness"] && by_material) {
      ctx.fail(n["youngs_modulus"] ? n["youngs_modulus"] : n["area"], "rods",
               "give either 'stiffness' (N/m) or 'youngs_modulus' and 'area' (EA/L), not both");
    }
    if (n["stiffness"]) p.stiffness = per_rod(n, "stiffness");
    if (by_material) {
      const double E = ctx.number(n, "youngs_modulus", ranges::youngs_modulus);
      const std::vector<double> A = per_rod(n, "area");
      for (int i = 0; i < rods; ++i) {
        p.stiffness.push_back(E * A[static_cast<size_t>(i)] / geometry.rods[static_cast<size_t>(i)].length);
      }
    }
    if (n["damping"]) p.damping = per_rod(n, "damping");
    if (const YAML::Node u = n["uncertainty"]) {
      within("rods.uncertainty", [&] {
        ctx.expect_map(u, "uncertainty", {"stiffness"});
        if (u["stiffness"]) p.stiffness_uncertainty = ctx.number(u, "stiffness");
      });
    }
    return p;
  }

  rig::SensorOptions sensors(const YAML::Node& s) const {
    ctx.expect_map(s, "sensors", {"sample_rate", "load_cell", "encoder"});
    rig::SensorOptions o;
    o.sample_rate_hz = ctx.number_or(s, "sample_rate", o.sample_rate_hz, ranges::sample_rate);
    if (s["load_cell"]) {
      within("sensors.load_cell", [&] {
        const YAML::Node lc = s["load_cell"];
        ctx.expect_map(lc, "load_cell", {"noise", "resolution"});
        o.force_noise_n = ctx.number_or(lc, "noise", 0.0);
        o.force_resolution_n = ctx.number_or(lc, "resolution", 0.0);
      });
    }
    if (s["encoder"]) {
      within("sensors.encoder", [&] {
        const YAML::Node e = s["encoder"];
        ctx.expect_map(e, "encoder", {"bits", "noise"});
        o.encoder_bits = ctx.integer_or(e, "bits", 0);
        o.angle_noise_rad = ctx.number_or(e, "noise", 0.0);
      });
    }
    return o;
  }

  rig::ReleaseOptions release(const YAML::Node& r) const {
    ctx.expect_map(r, "release", {"push_duration", "push_acceleration", "push_yaw_acceleration", "initial"});
    rig::ReleaseOptions o;
    o.push_duration_s = ctx.number_or(r, "push_duration", o.push_duration_s);
    if (r["push_acceleration"]) {
      const auto a = ctx.numbers(r, "push_acceleration", 2);
      o.push_acceleration = {a[0], a[1]};
    }
    o.push_yaw_acceleration = ctx.number_or(r, "push_yaw_acceleration", o.push_yaw_acceleration);
    if (r["initial"]) {
      const YAML::Node list = r["initial"];
      ctx.expect_sequence(list, "initial");
      for (const auto& e : list) {
        within("release.initial[" + std::to_string(o.initial.size() + 1) + "]", [&] {
          ctx.expect_map(e, "initial[]", {"x", "y", "yaw", "velocity", "angular_velocity"});
          rig::InitialCondition ic;
          ic.x = ctx.number_or(e, "x", 0.0);
          ic.y = ctx.number_or(e, "y", 0.0);
          ic.yaw = ctx.number_or(e, "yaw", 0.0);
          if (e["velocity"]) ic.velocity = ctx.vec3(e, "velocity");
          if (e["angular_velocity"]) ic.angular_velocity = ctx.vec3(e, "angular_velocity");
          o.initial.push_back(ic);
        });
      }
    }
    return o;
  }

  rig::SimulationOptions simulation(const YAML::Node& s) const {
    ctx.expect_map(s, "simulation",
                   {"method", "relative_tolerance", "position_tolerance", "max_step", "max_order", "resolve_hz"});
    rig::SimulationOptions o;
    const std::string method = ctx.text_or(s, "method", "generalized-alpha");
    if (method == "bdf") {
      o.method = rig::IntegrationMethod::bdf;
    } else if (method != "generalized-alpha") {
      ctx.fail(s["method"], "simulation.method", "unknown method '" + method + "' (generalized-alpha, bdf)");
    }
    o.relative_tolerance = ctx.number_or(s, "relative_tolerance", o.relative_tolerance);
    o.position_tolerance = ctx.number_or(s, "position_tolerance", o.position_tolerance);
    o.max_step_s = ctx.number_or(s, "max_step", o.max_step_s);
    o.max_order = ctx.integer_or(s, "max_order", o.max_order);
    o.resolve_hz = ctx.number_or(s, "resolve_hz", o.resolve_hz);
    return o;
  }

  // A flexible frame as the file gives it: a `rigflex reduce` export, read,
  // or a frame model read with the reduction asked for. Reduced and placed on
  // the joints later, by rig::resolve_frames.
  rig::FrameSource frame(const YAML::Node& e, const std::string& key, bool fixed) const {
    rig::FrameSource s;
    s.fixed = fixed;
    s.matching = matching(e);
    s.effect = {ctx.file(), YamlContext::line_of(e), key};
    const bool exported = static_cast<bool>(e["reduced"]);
    if (exported == static_cast<bool>(e["model"])) ctx.fail(e, key, "needs exactly one of 'reduced' or 'model'");
    if (exported) {
      const std::filesystem::path dir = base / ctx.text(e, "reduced");
      try {
        s.reduced = read_reduced_frame(dir);
        return s;
      } catch (const InputError&) {
        throw;
      } catch (const std::exception& x) {
        ctx.fail(e["reduced"], key + ".reduced", x.what());
      }
    }
    const std::filesystem::path file = base / ctx.text(e, "model");
    // Named here: the model reader's own error would not say which rig key points at it.
    if (!std::filesystem::is_regular_file(file)) ctx.fail(e["model"], key + ".model", "no such file: " + file.string());
    ModelFile model = read_model(file);
    s.model = std::move(model.model);
    s.model_name = model.name;
    s.model_key = {ctx.file(), YamlContext::line_of(e["model"]), key + ".model"};
    reduction::FrameReductionOptions& o = s.reduction;
    o.interface_set = ctx.text(e, "interface");
    const std::string method = ctx.text_or(e, "method", "guyan");
    const auto m = reduction::parse_reduction_method(method);
    if (!m) ctx.fail(e["method"], "method", "unknown method '" + method + "' (guyan, craig-bampton)");
    o.method = *m;
    o.modes = ctx.integer_or(e, "modes", 0);
    o.cutoff_hz = ctx.optional_number(e, "cutoff");
    o.support = fixed ? reduction::FrameSupport::grounded : reduction::FrameSupport::free;
    o.zeta = ctx.number_or(e, "zeta", 0.02);
    return s;
  }

  rig::FrameMatching matching(const YAML::Node& e) const {
    rig::FrameMatching m;
    if (e["offset"]) m.offset = ctx.vec3(e, "offset");
    m.tolerance = ctx.number_or(e, "tolerance", m.tolerance);
    return m;
  }

  // One effect, read by its kind in the catalogue (rig/effect_kinds.hpp);
  // a frame given by files is read here, when the kind asks for it.
  // An `uncertainty` the effect states goes to `uncertainty`, the rest to the kind.
  std::shared_ptr<const rig::Effect> effect(const rig::EffectKind& kind, const YAML::Node& e, const rig::RigGeometry& g,
                                            std::optional<rig::EffectUncertainty>& uncertainty) const {
    rig::EffectParseContext x;
    x.key = "effects." + kind.name;
    x.rods = rods;
    x.geometry = &g;
    x.body_mass = mass;
    x.read_frame = [&](bool fixed) { return frame(e, x.key, fixed); };
    try {
      rig::ParameterValue tree = parameter_tree(e);
      const rig::RangeScales scales = rig::range_scales(x);
      uncertainty = rig::take_uncertainty(kind, tree, rods, scales);
      rig::check_ranges(kind, tree, scales);
      return kind.parse(tree, x);
    } catch (const rig::ParameterError& p) {
      throw InputError(ctx.file(), p.line(), p.key(), p.reason());
    }
  }

  // The `effects` mapping: every effect switched on, in the file's order.
  void effects(const YAML::Node& effects, rig::RigModel& model) const {
    if (!effects.IsMap()) ctx.fail(effects, "effects", "must be a mapping of effect name to parameters");
    std::vector<std::string> seen;
    for (const auto& kv : effects) {
      const std::string name = kv.first.as<std::string>();
      const std::string key = "effects." + name;
      const YAML::Node& e = kv.second;
      const rig::EffectKind* kind = rig::find_effect_kind(name);
      // Checked before 'enabled': a misspelt effect switched off is still misspelt.
      if (!kind) ctx.fail(kv.first, key, "unknown effect '" + name + "' (known: " + rig::effect_name_list() + ")");
      if (!e.IsMap()) ctx.fail(e, key, "parameters must be a mapping");
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) ctx.fail(kv.first, key, "given twice");
      seen.push_back(name);
      // An effects file added to a model replaces the model's effect of that
      // name (and `enabled: false` there removes it).
      std::erase_if(model.effects, [&](const auto& x) { return name == x->name(); });
      std::erase_if(model.effect_uncertainty, [&](const auto& x) { return name == x.effect; });
      if (!within(key, [&] { return ctx.boolean_or(e, "enabled", true); })) continue;
      std::optional<rig::EffectUncertainty> uncertainty;
      model.effects.push_back(within(key, [&] { return effect(*kind, e, model.geometry, uncertainty); }));
      if (uncertainty) model.effect_uncertainty.push_back(std::move(*uncertainty));
    }
  }
};

// Why `name` cannot be a rig name, or "": it is written on one "# rig: name"
// line of every measurement file (and into check.json), so no line breaks or
// other control characters, and no blanks at either end.
std::string name_problem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r') return "must be one line (it contains a line break)";
    if (u < 0x20 || u == 0x7f) return "must not contain control characters (character code " + std::to_string(u) + ")";
  }
  if (name.front() == ' ' || name.back() == ' ') return "must not start or end with a blank";
  return "";
}

// The rig's name when the file gives none: the file's stem, with control
// characters replaced and blanks trimmed (a file may be called " rig\n.yaml").
std::string default_name(const std::string& source) {
  std::string stem = std::filesystem::path(source).stem().string();
  for (char& c : stem) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = '_';
  }
  const auto first = stem.find_first_not_of(' ');
  if (first == std::string::npos) return "rig";
  return stem.substr(first, stem.find_last_not_of(' ') - first + 1);
}

// The node a validation message's field path ("geometry.rods[2].length") names.
YAML::Node node_at(const YAML::Node& root, const std::string& path) {
  YAML::Node n = root;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '.')) {
    std::string name = part;
    int index = -1;
    if (const auto b = part.find('['); b != std::string::npos) {
      name = part.substr(0, b);
      index = std::stoi(part.substr(b + 1)) - 1;
    }
    const YAML::Node next = n[name];
    if (!next) return n;
    n = next;
    if (index >= 0 && n.IsSequence() && index < static_cast<int>(n.size())) n = n[index];
  }
  return n;
}

}  // namespace

// parse_rig_spec and add_effects without guard_yaml.
static rig::RigSpec parse_rig_spec_unguarded(const std::string& yaml_text, const std::string& source,
                                             const std::filesystem::path& base) {
  const YAML::Node root = load_yaml(yaml_text, source);
  RigFileReader r{YamlContext(source), base};
  const YamlContext& ctx = r.ctx;
  if (!root.IsMap()) throw InputError(source, 1, "", "a rig file is a mapping with at least 'geometry' and 'body'");
  ctx.expect_map(root, "rig", {"name", "geometry", "body", "rods", "sensors", "release", "simulation", "effects"});
  rig::RigModel model;
  if (root["name"]) {
    model.name = ctx.text(root, "name");
    if (const std::string why = name_problem(model.name); !why.empty()) ctx.fail(root["name"], "name", why);
  } else {
    model.name = default_name(source);
  }
  model.geometry = r.within("geometry", [&] { return r.geometry(ctx.required(root, "geometry")); });
  r.rods = model.geometry.rod_count();
  if (r.rods != 3 && r.rods != 4) {
    ctx.fail(root["geometry"]["rods"], "geometry.rods", "a rig has 3 or 4 rods (got " + std::to_string(r.rods) + ")");
  }
  model.body = r.within("body", [&] { return r.body(ctx.required(root, "body")); });
  model.body_uncertainty = r.body_uncertainty(root["body"]);
  if (root["rods"]) model.rods = r.within("rods", [&] { return r.rod_properties(root["rods"], model.geometry); });
  if (root["sensors"]) model.sensors = r.within("sensors", [&] { return r.sensors(root["sensors"]); });
  if (root["release"]) model.release = r.within("release", [&] { return r.release(root["release"]); });
  if (root["simulation"]) model.simulation = r.within("simulation", [&] { return r.simulation(root["simulation"]); });
  r.mass = model.body.mass;
  if (root["effects"]) r.effects(root["effects"], model);
  try {
    model.validate_input();
  } catch (const std::invalid_argument& x) {
    const std::string msg = x.what();
    const auto colon = msg.find(':');
    const std::string field = msg.substr(0, colon);
    const YAML::Node at = node_at(root, field);
    throw InputError(source, YamlContext::line_of(at), field, colon == std::string::npos ? msg : msg.substr(colon + 2));
  }
  return rig::RigSpec{std::move(model)};
}

rig::RigModel resolve_rig(const rig::RigSpec& spec, const RigReadOptions& options) {
  try {
    return rig::resolve_frames(spec, options);
  } catch (const rig::SpecError& e) {
    throw InputError(e.where().file, e.where().line, e.where().key, e.reason());
  }
}

rig::RigModel parse_rig(const std::string& yaml_text, const std::string& source, const std::filesystem::path& base,
                        const RigReadOptions& options) {
  return resolve_rig(parse_rig_spec(yaml_text, source, base), options);
}

InputError no_equilibrium_error(const std::filesystem::path& file, const rig::RigModel& model,
                                const std::string& detail) {
  std::string key = "geometry";
  std::string advice = "the rods' joint centres and lengths hold the body nowhere near the nominal pose";
  if (detail.rfind("initial condition", 0) == 0) {
    key = "release.initial";
    advice = "an initial displacement is too large for the rig to hold";
  } else {
    for (const auto& e : model.effects) {
      const std::string name = e->name();
      if (name == "rod_compliance" || name == "fixed_frame_flexibility" || name == "carrying_frame_flexibility" ||
          name == "rod_length_error" || name == "joint_position_error") {
        key = "effects." + name;
        advice = "with this effect the rig holds the body nowhere near the nominal pose (too soft, or too large an "
                 "error?)";
        break;
      }
    }
    if (key == "geometry" && !model.rods.stiffness.empty()) {
      key = "rods.stiffness";
      advice = "with these rods the rig holds the body nowhere near the nominal pose (too soft?)";
    }
  }
  int line = 0;
  try {
    line = YamlContext::line_of(node_at(YAML::LoadFile(file.string()), key));
  } catch (const YAML::Exception&) {
    // The file was read once already; without it, the error names no line.
  }
  return InputError(file.string(), line, key, detail + ": " + advice);
}

rig::RigSpec read_rig_spec(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the rig file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_rig_spec(ss.str(), file.string(), file.parent_path());
}

rig::RigModel read_rig(const std::filesystem::path& file, const RigReadOptions& options) {
  return resolve_rig(read_rig_spec(file), options);
}

static void add_effects_unguarded(rig::RigModel& model, const std::filesystem::path& file,
                                  const RigReadOptions& options) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the effects file");
  std::stringstream ss;
  ss << in.rdbuf();
  const YAML::Node root = load_yaml(ss.str(), file.string());
  RigFileReader r{YamlContext(file.string()), file.parent_path()};
  if (!root.IsMap() || !root["effects"]) {
    throw InputError(file.string(), 1, "effects", "an effects file is a mapping with the one key 'effects'");
  }
  r.ctx.expect_map(root, "effects file", {"effects"});
  r.rods = model.geometry.rod_count();
  r.mass = model.body.mass;
  r.effects(root["effects"], model);
  model = resolve_rig(rig::RigSpec{std::move(model)}, options);
  try {
    model.validate();
  } catch (const std::invalid_argument& x) {
    throw InputError(file.string(), YamlContext::line_of(root["effects"]), "effects", x.what());
  }
}

rig::RigSpec parse_rig_spec(const std::string& yaml_text, const std::string& source,
                            const std::filesystem::path& base) {
  return guard_yaml(source, [&] { return parse_rig_spec_unguarded(yaml_text, source, base); });
}

void add_effects(rig::RigModel& model, const std::filesystem::path& file, const RigReadOptions& options) {
  guard_yaml(file.string(), [&] { add_effects_unguarded(model, file, options); });
}

}  // namespace rigflex::io
