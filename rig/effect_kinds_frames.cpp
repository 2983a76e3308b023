// The flexible frames: a reduced frame model from a file (read by io/), or,
// as diagnose fits them, the compliance of the frame's joints
// (rig/joint_compliance.hpp).
#include "rig/effect_kind_entries.hpp"
#include "rig/effects.hpp"
#include "rig/joint_compliance.hpp"

namespace rigflex::rig::kinds {
namespace {

using R = ParameterReader;

// The keys of a frame given by a model or an export, for the docs and for
// the check of a file's keys.
std::vector<ParameterSpec> frame_parameters(const std::string& joint_compliance_doc) {
  return {
      {"reduced", ParameterShape::text, "", -INFINITY, INFINITY, false, "", "folder of a `rigflex reduce` export (or `model`)"},
      {"model", ParameterShape::text, "", -INFINITY, INFINITY, false, "", "frame model file, reduced on reading"},
      {"interface", ParameterShape::text, "", -INFINITY, INFINITY, false, "", "the model's node set at the joints"},
      {"method", ParameterShape::text, "", -INFINITY, INFINITY, false, "guyan", "guyan or craig-bampton"},
      {"modes", ParameterShape::integer, "1", 0, INFINITY, false, "0", "Craig-Bampton modes kept"},
      {"cutoff", ParameterShape::number, "Hz", 0, INFINITY, true, "", "Craig-Bampton modes kept below it"},
      {"zeta", ParameterShape::number, "1", 0, 1, false, "0.02", "modal damping ratio"},
      {"offset", ParameterShape::vec3, "m", -INFINITY, INFINITY, false, "", "model origin in the rig's frame"},
      {"tolerance", ParameterShape::number, "m", 0, INFINITY, true, "0.01", "joint centre to interface node"},
      {"joint_compliance", ParameterShape::map, "", -INFINITY, INFINITY, false, "", joint_compliance_doc},
  };
}

void non_negative(const Vec3& v, const ParameterValue& node, const std::string& key) {
  if (!(v.minCoeff() >= 0)) R::fail(node, key, "compliances must be >= 0 (m/N; rocking, twist rad/(N m))");
}

Eigen::Vector2d compliance_pair(const ParameterValue& c, const std::string& at, const char* k) {
  Eigen::Vector2d v = Eigen::Vector2d::Zero();
  const ParameterValue& node = c[k];
  if (!node.defined()) return v;
  const std::string key = at + "." + k;
  if (node.kind != ParameterValue::Kind::list || node.items.size() != 2) R::fail(node, key, "needs [x, y]");
  // Read before assigning: a comma initializer left half-filled by a throw
  // asserts as it unwinds (found by fuzzing).
  v.x() = R::as_number(node.items[0], key);
  v.y() = R::as_number(node.items[1], key);
  non_negative(Vec3(v.x(), v.y(), 0.0), node, key);
  return v;
}

// The frame model's construction, its invalid_argument named at `key`.
template <class F>
std::shared_ptr<const Effect> guarded(const ParameterValue& at, const std::string& key, F make) {
  try {
    return make();
  } catch (const std::invalid_argument& x) {
    R::fail(at, key, x.what());
  }
}

std::shared_ptr<const Effect> fixed_joint_compliance(const ParameterValue& e, const EffectParseContext& x) {
  R::expect_map(e, x.key, {"enabled", "joint_compliance"});
  const ParameterValue& c = e["joint_compliance"];
  const std::string at = x.key + ".joint_compliance";
  R::within(at, [&] { R::expect_map(c, at, {"joints", "sway", "twist"}); });
  FixedJointCompliance jc;
  jc.joints = R::within(at, [&] { return R::per_rod_vectors(c, "joints", x.rods); });
  for (const auto& v : jc.joints) non_negative(v, c["joints"], at + ".joints");
  jc.sway = compliance_pair(c, at, "sway");
  jc.twist = R::number_or(c, "twist", 0.0);
  non_negative(Vec3(jc.twist, 0, 0), c["twist"], at + ".twist");
  return guarded(c, at, [&] {
    return std::make_shared<FixedFrameFlexibility>(joint_compliance_fixed_frame(*x.geometry, x.body_mass, jc));
  });
}

std::shared_ptr<const Effect> carrying_joint_compliance(const ParameterValue& e, const EffectParseContext& x) {
  R::expect_map(e, x.key, {"enabled", "joint_compliance"});
  const ParameterValue& c = e["joint_compliance"];
  const std::string at = x.key + ".joint_compliance";
  R::within(at, [&] { R::expect_map(c, at, {"translation", "rocking"}); });
  CarryingJointCompliance jc;
  if (c["translation"].defined()) jc.translation = R::vec3(c, "translation");
  non_negative(jc.translation, c["translation"], at + ".translation");
  jc.rocking = compliance_pair(c, at, "rocking");
  return guarded(c, at, [&] {
    return std::make_shared<CarryingFrameFlexibility>(joint_compliance_carrying_frame(*x.geometry, x.body_mass, jc));
  });
}

// A frame given by a model or an export: the files are io/'s to read.
std::shared_ptr<const Effect> frame_from_files(const EffectKind& kind, const ParameterValue& e,
                                               const EffectParseContext& x, bool fixed) {
  std::vector<std::string> keys = allowed_keys(kind);
  std::erase(keys, "joint_compliance");
  R::expect_map(e, x.key, keys);
  return std::make_shared<PendingFrame>(x.read_frame(fixed));
}

FixedJointCompliance fixed_compliance(const Eigen::VectorXd& p, int n) {
  FixedJointCompliance f;
  for (int i = 0; i < n; ++i) f.joints.push_back(p.segment<3>(3 * i).cwiseMax(0.0));
  f.sway = p.segment<2>(3 * n).cwiseMax(0.0);
  f.twist = positive(p(3 * n + 2));
  return f;
}

CarryingJointCompliance carrying_compliance(const Eigen::VectorXd& p) {
  CarryingJointCompliance c;
  c.translation = p.head<3>().cwiseMax(0.0);
  c.rocking = p.segment<2>(3).cwiseMax(0.0);
  return c;
}

EffectFitting fit_fixed(const FitContext& x) {
  const FitScales s = fit_scales(x);
  const int n = s.n;
  const double c_probe = s.c_probe, rho = s.rho;
  EffectFitting f;
  for (int i = 1; i <= n; ++i) {
    for (const char* a : {"x", "y", "z"}) {
      f.parameters.push_back({"joint" + std::to_string(i) + "_" + a + "_compliance", "m/N", c_probe, 0,
                              std::string(a) == "z" ? s.c_high : s.c_side, true});
    }
  }
  f.parameters.push_back({"sway_x_compliance", "m/N", c_probe / n, 0, s.c_side, true});
  f.parameters.push_back({"sway_y_compliance", "m/N", c_probe / n, 0, s.c_side, true});
  f.parameters.push_back({"twist_compliance", "rad/(N m)", c_probe / (n * rho * rho), 0, s.c_side / (rho * rho), true});
  f.make = [x, c_probe, rho, n](const Eigen::VectorXd& p) -> std::shared_ptr<const Effect> {
    Eigen::VectorXd size = p.cwiseMax(0.0);
    size(3 * n + 2) *= rho * rho;
    if (size.maxCoeff() < 1e-2 * c_probe) return nullptr;
    return std::make_shared<FixedFrameFlexibility>(
        joint_compliance_fixed_frame(x.geometry, x.body_mass, fixed_compliance(p, n)));
  };
  f.write = [n](const Eigen::VectorXd& p) {
    const FixedJointCompliance c = fixed_compliance(p, n);
    std::vector<ParameterValue> joints;
    for (const auto& j : c.joints) joints.push_back(ParameterValue::of(Eigen::VectorXd(j)));
    ParameterValue jc = ParameterValue::map();
    jc.set("joints", ParameterValue::list(joints)).set("sway", ParameterValue::of(Eigen::VectorXd(c.sway)));
    jc.set("twist", ParameterValue::of(c.twist));
    return ParameterValue::map().set("joint_compliance", jc);
  };
  f.advice = "model the fixed frame with finite elements and reduce it onto the upper joints "
             "(effects.fixed_frame_flexibility.model, or a `rigflex reduce` export); the fitted joint compliance "
             "is a stand-in that captures its quasi-static part";
  f.stand_in = true;
  f.evidence = "an accelerometer or a dial gauge on the fixed frame at an upper joint: only the fixed frame's "
               "deformation moves it";
  return f;
}

EffectFitting fit_carrying(const FitContext& x) {
  const FitScales s = fit_scales(x);
  const double c_probe = s.c_probe, rho = s.rho;
  EffectFitting f;
  f.parameters = {{"x_compliance", "m/N", c_probe, 0, s.c_side, true},
                  {"y_compliance", "m/N", c_probe, 0, s.c_side, true},
                  {"z_compliance", "m/N", c_probe, 0, s.c_high, true},
                  {"rocking_x_compliance", "rad/(N m)", c_probe / (rho * rho), 0, s.c_side / (rho * rho), true},
                  {"rocking_y_compliance", "rad/(N m)", c_probe / (rho * rho), 0, s.c_side / (rho * rho), true}};
  f.make = [x, c_probe, rho](const Eigen::VectorXd& p) -> std::shared_ptr<const Effect> {
    Eigen::VectorXd size = p.cwiseMax(0.0);
    size.tail<2>() *= rho * rho;
    if (size.maxCoeff() < 1e-2 * c_probe) return nullptr;
    return std::make_shared<CarryingFrameFlexibility>(
        joint_compliance_carrying_frame(x.geometry, x.body_mass, carrying_compliance(p)));
  };
  f.write = [](const Eigen::VectorXd& p) {
    const CarryingJointCompliance c = carrying_compliance(p);
    ParameterValue jc = ParameterValue::map();
    jc.set("translation", ParameterValue::of(Eigen::VectorXd(c.translation)));
    jc.set("rocking", ParameterValue::of(Eigen::VectorXd(c.rocking)));
    return ParameterValue::map().set("joint_compliance", jc);
  };
  f.advice = "model the carrying frame with finite elements and reduce it free-free onto the lower joints "
             "(effects.carrying_frame_flexibility.model); the fitted plate compliance is a stand-in";
  f.stand_in = true;
  f.evidence = "accelerometers at two lower joints and on the body: the carrying frame deforms where they leave "
               "the body's rigid motion";
  return f;
}

}  // namespace

EffectKind fixed_frame_flexibility() {
  EffectKind k;
  k.name = "fixed_frame_flexibility";
  k.hook = EffectHook::build;
  k.equations = "the fixed frame reduced onto the upper joints, grounded: its K, M, C join the rig's equations";
  k.signature = "deformation modes of the frame; the check's fixed-frame share";
  k.parameters = frame_parameters("instead of files: `{joints: [[cx, cy, cz] per rod], sway: [sx, sy], twist}`, "
                                  "compliances in m/N, twist in rad/(N m)");
  k.parse = [](const ParameterValue& e, const EffectParseContext& x) -> std::shared_ptr<const Effect> {
    if (e["joint_compliance"].defined()) return fixed_joint_compliance(e, x);
    return frame_from_files(*find_effect_kind("fixed_frame_flexibility"), e, x, true);
  };
  k.fitted_through = "compliance of each upper joint along x, y, z (G) + the frame top's sway x, y and twist "
                     "(rig/joint_compliance.hpp)";
  k.fit = fit_fixed;
  return k;
}

EffectKind carrying_frame_flexibility() {
  EffectKind k;
  k.name = "carrying_frame_flexibility";
  k.hook = EffectHook::build;
  k.equations = "the carrying frame reduced free-free onto the lower joints, in modal coordinates about its mean "
                "axes: the joints move with its elastic modes";
  k.signature = "carrying-frame modes";
  k.parameters = frame_parameters("instead of files: `{translation: [cx, cy, cz], rocking: [rx, ry]}`, "
                                  "m/N, rocking in rad/(N m)");
  k.parse = [](const ParameterValue& e, const EffectParseContext& x) -> std::shared_ptr<const Effect> {
    if (e["joint_compliance"].defined()) return carrying_joint_compliance(e, x);
    return frame_from_files(*find_effect_kind("carrying_frame_flexibility"), e, x, false);
  };
  k.fitted_through = "the lower joints as one plate against the body: x, y, z and rocking about x, y";
  k.fit = fit_carrying;
  return k;
}

}  // namespace rigflex::rig::kinds
