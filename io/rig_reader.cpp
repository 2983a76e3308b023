#include "io/rig_reader.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "fe/error.hpp"
#include "io/model_reader.hpp"
#include "io/reduced_export.hpp"
#include "io/yaml_fields.hpp"
#include "reduction/frame_reduction.hpp"
#include "rig/effect.hpp"
#include "rig/effects.hpp"
#include "rig/frame_models.hpp"
#include "rig/rig_spec.hpp"
#include "rig/joint_compliance.hpp"

namespace rigflex::io {
namespace {

using rig::Vec3;

struct Reader {
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

  // Per-rod values: a list of n, or one value for all rods.
  std::vector<double> per_rod(const YAML::Node& map, const std::string& key) const {
    const YAML::Node v = ctx.required(map, key);
    if (v.IsScalar()) return std::vector<double>(rods, ctx.as_number(v, key));
    return ctx.numbers(map, key, rods);
  }

  std::vector<Vec3> per_rod_vectors(const YAML::Node& map, const std::string& key) const {
    const YAML::Node v = ctx.required(map, key);
    ctx.expect_sequence(v, key);
    if (static_cast<int>(v.size()) != rods) {
      ctx.fail(v, key, "needs one [x, y, z] per rod (" + std::to_string(rods) + "), got " + std::to_string(v.size()));
    }
    std::vector<Vec3> out;
    for (const auto& e : v) out.push_back(ctx.as_vec3(e, key));
    return out;
  }

  rig::RigGeometry geometry(const YAML::Node& g) const {
    ctx.expect_map(g, "geometry", {"gravity", "reference_point", "rods"});
    rig::RigGeometry out;
    out.gravity = ctx.number_or(g, "gravity", 9.80665);
    out.reference_point = ctx.vec3(g, "reference_point");
    const YAML::Node rods_node = ctx.required(g, "rods");
    ctx.expect_sequence(rods_node, "rods");
    for (const auto& r : rods_node) {
      // Rod i is entry i (1-based), as in the spec and RigModel::validate.
      within("geometry.rods[" + std::to_string(out.rods.size() + 1) + "]", [&] {
        ctx.expect_map(r, "rods[]", {"upper", "lower", "length", "encoder_axis"});
        rig::RodGeometry rod;
        rod.upper = ctx.vec3(r, "upper");
        rod.lower = ctx.vec3(r, "lower");
        rod.length = ctx.number(r, "length");
        rod.encoder_axis = ctx.vec3(r, "encoder_axis");
        out.rods.push_back(rod);
      });
    }
    return out;
  }

  fe::MassProperties body(const YAML::Node& b) const {
    ctx.expect_map(b, "body", {"mass", "cog", "inertia", "name"});
    fe::MassProperties m;
    m.mass = ctx.number(b, "mass");
    m.cog = ctx.vec3(b, "cog");
    const auto J = ctx.numbers(b, "inertia", 6);
    m.inertia = rig::inertia_tensor({J[0], J[1], J[2], J[3], J[4], J[5]});
    return m;
  }

  rig::SensorOptions sensors(const YAML::Node& s) const {
    ctx.expect_map(s, "sensors", {"sample_rate", "load_cell", "encoder"});
    rig::SensorOptions o;
    o.sample_rate_hz = ctx.number_or(s, "sample_rate", o.sample_rate_hz);
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

  std::shared_ptr<const rig::Effect> effect(const std::string& name, const YAML::Node& e,
                                            const rig::RigGeometry& g) const {
    const std::string key = "effects." + name;
    auto frame_keys = {"enabled", "reduced", "model", "interface", "method", "modes", "cutoff", "zeta", "offset",
                       "tolerance"};
    if ((name == "fixed_frame_flexibility" || name == "carrying_frame_flexibility") && e["joint_compliance"]) {
      return joint_compliance_frame(name, e, g);
    }
    if (name == "fixed_frame_flexibility" || name == "carrying_frame_flexibility") {
      ctx.expect_map(e, key, frame_keys);
      return std::make_shared<rig::PendingFrame>(frame(e, key, name == "fixed_frame_flexibility"));
    }
    if (name == "rod_compliance") {
      ctx.expect_map(e, key, {"enabled", "stiffness", "youngs_modulus", "area"});
      if (static_cast<bool>(e["stiffness"]) == static_cast<bool>(e["area"])) {
        ctx.fail(e, key, "needs either 'stiffness' (N/m per rod) or 'youngs_modulus' and 'area' (EA/L)");
      }
      if (e["stiffness"]) return std::make_shared<rig::RodCompliance>(per_rod(e, "stiffness"));
      const double E = ctx.number(e, "youngs_modulus");
      const auto A = per_rod(e, "area");
      std::vector<double> k;
      for (int i = 0; i < rods; ++i) k.push_back(E * A[i] / g.rods[i].length);
      return std::make_shared<rig::RodCompliance>(k);
    }
    if (name == "rod_mass") {
      ctx.expect_map(e, key, {"enabled", "mass"});
      return std::make_shared<rig::RodMass>(per_rod(e, "mass"));
    }
    if (name == "joint_friction") {
      ctx.expect_map(e, key, {"enabled", "viscous", "coulomb", "regularization", "joints"});
      rig::JointFrictionParameters p;
      if (!e["viscous"] && !e["coulomb"]) ctx.fail(e, key, "needs 'viscous' (N m s/rad) and/or 'coulomb' (N m)");
      p.viscous = ctx.number_or(e, "viscous", 0.0);
      p.coulomb = ctx.number_or(e, "coulomb", 0.0);
      p.regularization = ctx.number_or(e, "regularization", p.regularization);
      const std::string joints = ctx.text_or(e, "joints", "both");
      if (joints != "both" && joints != "upper" && joints != "lower") {
        ctx.fail(e["joints"], "joints", "must be both, upper or lower");
      }
      p.upper = joints != "lower";
      p.lower = joints != "upper";
      return std::make_shared<rig::JointFriction>(p);
    }
    if (name == "air_drag") {
      ctx.expect_map(e, key, {"enabled", "density", "cd_area", "rotational", "centre"});
      rig::AirDragParameters p;
      p.density = ctx.number_or(e, "density", p.density);
      if (!e["cd_area"] && !e["rotational"]) ctx.fail(e, key, "needs 'cd_area' (m^2) and/or 'rotational'");
      p.cd_area = ctx.number_or(e, "cd_area", 0.0);
      p.rotational = ctx.number_or(e, "rotational", 0.0);
      if (e["centre"]) p.centre = ctx.vec3(e, "centre");
      return std::make_shared<rig::AirDrag>(p);
    }
    if (name == "encoder_offset") {
      ctx.expect_map(e, key, {"enabled", "alpha", "beta"});
      return std::make_shared<rig::EncoderOffset>(per_rod(e, "alpha"), per_rod(e, "beta"));
    }
    if (name == "rod_length_error") {
      ctx.expect_map(e, key, {"enabled", "delta"});
      return std::make_shared<rig::RodLengthError>(per_rod(e, "delta"));
    }
    if (name == "joint_position_error") {
      ctx.expect_map(e, key, {"enabled", "upper", "lower"});
      const auto zero = std::vector<Vec3>(rods, Vec3::Zero());
      return std::make_shared<rig::JointPositionError>(e["upper"] ? per_rod_vectors(e, "upper") : zero,
                                                       e["lower"] ? per_rod_vectors(e, "lower") : zero);
    }
    if (name == "load_cell_gain") {
      ctx.expect_map(e, key, {"enabled", "gain", "offset"});
      if (!e["gain"] && !e["offset"]) ctx.fail(e, key, "needs 'gain' and/or 'offset' (N)");
      return std::make_shared<rig::LoadCellGain>(e["gain"] ? per_rod(e, "gain") : std::vector<double>(rods, 1.0),
                                                 e["offset"] ? per_rod(e, "offset") : std::vector<double>(rods, 0.0));
    }
    std::string known;
    for (const char* n : rig::effect_names()) known += std::string(known.empty() ? "" : ", ") + n;
    ctx.fail(e, key, "unknown effect '" + name + "' (known: " + known + ")");
  }

  // A frame given by the compliance of its joints (rig/joint_compliance.hpp),
  // as `rigflex diagnose` fits it.
  std::shared_ptr<const rig::Effect> joint_compliance_frame(const std::string& name, const YAML::Node& e,
                                                            const rig::RigGeometry& g) const {
    const std::string key = "effects." + name;
    ctx.expect_map(e, key, {"enabled", "joint_compliance"});
    const YAML::Node c = e["joint_compliance"];
    const std::string at = key + ".joint_compliance";
    auto non_negative = [&](const Vec3& v, const YAML::Node& node, const std::string& k) {
      if (!(v.minCoeff() >= 0)) ctx.fail(node, at + "." + k, "compliances must be >= 0 (m/N; rocking, twist rad/(N m))");
    };
    auto pair = [&](const char* k) {
      Eigen::Vector2d v = Eigen::Vector2d::Zero();
      if (!c[k]) return v;
      if (!c[k].IsSequence() || c[k].size() != 2) ctx.fail(c[k], at + "." + k, "needs [x, y]");
      v << ctx.as_number(c[k][0], at + "." + k), ctx.as_number(c[k][1], at + "." + k);
      non_negative(Vec3(v.x(), v.y(), 0.0), c[k], k);
      return v;
    };
    if (name == "fixed_frame_flexibility") {
      within(at, [&] { ctx.expect_map(c, at, {"joints", "sway", "twist"}); });
      rig::FixedJointCompliance jc;
      jc.joints = within(at, [&] { return per_rod_vectors(c, "joints"); });
      for (const auto& v : jc.joints) non_negative(v, c["joints"], "joints");
      jc.sway = pair("sway");
      jc.twist = ctx.number_or(c, "twist", 0.0);
      non_negative(Vec3(jc.twist, 0, 0), c["twist"], "twist");
      return guarded(c, at, [&] {
        return std::make_shared<rig::FixedFrameFlexibility>(rig::joint_compliance_fixed_frame(g, mass, jc));
      });
    }
    within(at, [&] { ctx.expect_map(c, at, {"translation", "rocking"}); });
    rig::CarryingJointCompliance jc;
    if (c["translation"]) jc.translation = ctx.vec3(c, "translation");
    non_negative(jc.translation, c["translation"], "translation");
    jc.rocking = pair("rocking");
    return guarded(c, at, [&] {
      return std::make_shared<rig::CarryingFrameFlexibility>(rig::joint_compliance_carrying_frame(g, mass, jc));
    });
  }

  // The `effects` mapping: every effect switched on, in the file's order.
  void effects(const YAML::Node& effects, rig::RigModel& model) const {
    if (!effects.IsMap()) ctx.fail(effects, "effects", "must be a mapping of effect name to parameters");
    std::vector<std::string> seen;
    for (const auto& kv : effects) {
      const std::string name = kv.first.as<std::string>();
      const std::string key = "effects." + name;
      const YAML::Node& e = kv.second;
      bool known = false;
      std::string names;
      for (const char* n : rig::effect_names()) {
        known = known || name == n;
        names += std::string(names.empty() ? "" : ", ") + n;
      }
      // Checked before 'enabled': a misspelt effect switched off is still misspelt.
      if (!known) ctx.fail(kv.first, key, "unknown effect '" + name + "' (known: " + names + ")");
      if (!e.IsMap()) ctx.fail(e, key, "parameters must be a mapping");
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) ctx.fail(kv.first, key, "given twice");
      seen.push_back(name);
      // An effects file added to a model replaces the model's effect of that
      // name (and `enabled: false` there removes it).
      std::erase_if(model.effects, [&](const auto& x) { return name == x->name(); });
      if (!within(key, [&] { return ctx.boolean_or(e, "enabled", true); })) continue;
      model.effects.push_back(within(key, [&] { return effect(name, e, model.geometry); }));
    }
  }

  template <class F>
  std::shared_ptr<const rig::Effect> guarded(const YAML::Node& e, const std::string& key, F make) const {
    try {
      return make();
    } catch (const std::invalid_argument& x) {
      ctx.fail(e, key, x.what());
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

rig::RigSpec parse_rig_spec(const std::string& yaml_text, const std::string& source,
                            const std::filesystem::path& base) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source, e.mark.line + 1, "", std::string("malformed YAML: ") + e.msg);
  }
  Reader r{YamlContext(source), base};
  const YamlContext& ctx = r.ctx;
  if (!root.IsMap()) throw InputError(source, 1, "", "a rig file is a mapping with at least 'geometry' and 'body'");
  ctx.expect_map(root, "rig", {"name", "geometry", "body", "sensors", "release", "simulation", "effects"});
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
  if (root["sensors"]) model.sensors = r.within("sensors", [&] { return r.sensors(root["sensors"]); });
  if (root["release"]) model.release = r.within("release", [&] { return r.release(root["release"]); });
  if (root["simulation"]) model.simulation = r.within("simulation", [&] { return r.simulation(root["simulation"]); });
  r.mass = model.body.mass;
  if (root["effects"]) r.effects(root["effects"], model);
  try {
    model.validate();
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
    return rig::resolve_frames(spec, options.progress);
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

void add_effects(rig::RigModel& model, const std::filesystem::path& file, const RigReadOptions& options) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the effects file");
  std::stringstream ss;
  ss << in.rdbuf();
  YAML::Node root;
  try {
    root = YAML::Load(ss.str());
  } catch (const YAML::ParserException& e) {
    throw InputError(file.string(), e.mark.line + 1, "", std::string("malformed YAML: ") + e.msg);
  }
  Reader r{YamlContext(file.string()), file.parent_path()};
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

}  // namespace rigflex::io
