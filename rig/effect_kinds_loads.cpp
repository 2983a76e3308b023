// Effects that load the moving rig (the add_loads hook): friction in the
// joints and the air's drag on the body.
#include "rig/effect_kind_entries.hpp"
#include "rig/effects.hpp"

namespace rigflex::rig::kinds {
namespace {

using R = ParameterReader;

std::shared_ptr<const Effect> parse_joint_friction(const ParameterValue& e, const EffectParseContext& x) {
  expect_parameters(e, x, "joint_friction");
  JointFrictionParameters p;
  if (!e["viscous"].defined() && !e["coulomb"].defined()) {
    R::fail(e, x.key, "needs 'viscous' (N m s/rad) and/or 'coulomb' (N m)");
  }
  p.viscous = R::number_or(e, "viscous", 0.0);
  p.coulomb = R::number_or(e, "coulomb", 0.0);
  p.regularization = R::number_or(e, "regularization", p.regularization);
  const std::string joints = R::text_or(e, "joints", "both");
  if (joints != "both" && joints != "upper" && joints != "lower") R::fail(e["joints"], "joints", "must be both, upper or lower");
  p.upper = joints != "lower";
  p.lower = joints != "upper";
  return std::make_shared<JointFriction>(p);
}

std::shared_ptr<const Effect> parse_air_drag(const ParameterValue& e, const EffectParseContext& x) {
  expect_parameters(e, x, "air_drag");
  AirDragParameters p;
  p.density = R::number_or(e, "density", p.density);
  if (!e["cd_area"].defined() && !e["rotational"].defined()) R::fail(e, x.key, "needs 'cd_area' (m^2) and/or 'rotational'");
  p.cd_area = R::number_or(e, "cd_area", 0.0);
  p.rotational = R::number_or(e, "rotational", 0.0);
  if (e["centre"].defined()) p.centre = R::vec3(e, "centre");
  return std::make_shared<AirDrag>(p);
}

// Viscous and Coulomb torque, both joints of every rod.
EffectFitting fit_joint_friction(const FitContext& x) {
  const FitScales s = fit_scales(x);
  // A damping ratio of about 1e-3 of the swing from the viscous probe; the
  // Coulomb probe dissipates about as much at 0.02 rad of swing.
  const double viscous = 2e-3 * s.M * s.L * s.L * s.w / (2.0 * s.n);
  const double w = s.w;
  EffectFitting f;
  f.parameters = {{"viscous", "N m s/rad", viscous, 0, 1000 * viscous, true},
                  {"coulomb", "N m", viscous * 0.02 * w, 0, 1000 * viscous * 0.02 * w, true}};
  f.make = [](const Eigen::VectorXd& p) -> std::shared_ptr<const Effect> {
    JointFrictionParameters j;
    j.viscous = positive(p(0));
    j.coulomb = positive(p(1));
    if (j.viscous <= 0 && j.coulomb <= 0) return nullptr;
    return std::make_shared<JointFriction>(j);
  };
  f.write = [](const Eigen::VectorXd& p) {
    return ParameterValue::map()
        .set("viscous", ParameterValue::of(positive(p(0))))
        .set("coulomb", ParameterValue::of(positive(p(1))));
  };
  f.advice = "add joint friction (effects.joint_friction), or service the Hooke's joints' bearings";
  f.evidence = "records at two swing amplitudes: Coulomb friction takes the same amplitude per cycle, viscous "
               "friction the same share, air drag a share that grows with the amplitude";
  return f;
}

// Drag area at the CoG and rotational drag.
EffectFitting fit_air_drag(const FitContext& x) {
  const FitScales s = fit_scales(x);
  // Drag is linear in both parameters; the probes damp the swing by a
  // ratio of about 1e-3 at 0.05 rad of swing (far above the integrator's
  // rounding) and are no statement of what is plausible.
  const double rotational = 0.02 * s.M * s.rho * s.rho;
  EffectFitting f;
  f.parameters = {{"cd_area", "m^2", 0.08 * s.M / s.L, 0, 30.0, true},
                  {"rotational", "N m s^2/rad^2", rotational, 0, 1e3 * rotational, true}};
  f.make = [](const Eigen::VectorXd& p) -> std::shared_ptr<const Effect> {
    AirDragParameters d;
    d.cd_area = positive(p(0));
    d.rotational = positive(p(1));
    if (d.cd_area <= 0 && d.rotational <= 0) return nullptr;
    return std::make_shared<AirDrag>(d);
  };
  f.write = [](const Eigen::VectorXd& p) {
    return ParameterValue::map()
        .set("cd_area", ParameterValue::of(positive(p(0))))
        .set("rotational", ParameterValue::of(positive(p(1))));
  };
  f.advice = "add air drag (effects.air_drag: the body's drag area), or shield the body from drafts";
  f.evidence = "records at two swing amplitudes (drag takes a share per cycle that grows with the amplitude, "
               "joint friction does not), or one with the body shielded from the air";
  return f;
}

}  // namespace

EffectKind joint_friction() {
  EffectKind k;
  k.name = "joint_friction";
  k.hook = EffectHook::add_loads;
  k.equations = "torque -(c w + mu w / sqrt(w.w + eps^2)) in each Hooke's joint against the rod's relative swing "
                "rate w, balanced by transverse end forces on the rod";
  k.signature = "Coulomb: amplitude decays linearly; viscous: exponentially";
  k.parameters = {
      {"viscous", ParameterShape::number, "N m s/rad", 0, inf, false, "0", "c (`viscous` and/or `coulomb`)"},
      {"coulomb", ParameterShape::number, "N m", 0, inf, false, "0", "mu"},
      {"regularization", ParameterShape::number, "rad/s", 0, inf, true, "0.001",
       "eps: below it Coulomb friction turns viscous"},
      {"joints", ParameterShape::text, "", -inf, inf, false, "both", "both, upper or lower"},
  };
  k.parse = parse_joint_friction;
  k.fitted_through = "viscous and Coulomb torque, both joints of every rod";
  k.fit = fit_joint_friction;
  return k;
}

EffectKind air_drag() {
  EffectKind k;
  k.name = "air_drag";
  k.hook = EffectHook::add_loads;
  k.equations = "force -1/2 rho CdA norm(v) v on the body at the drag centre and moment -c_rot norm(w) w";
  k.signature = "large swings decay faster";
  k.parameters = {
      {"density", ParameterShape::number, "kg/m^3", 0, 10, true, "1.2", "air density"},
      {"cd_area", ParameterShape::number, "m^2", 0, 100, false, "0",
       "drag coefficient x frontal area (`cd_area` and/or `rotational`)"},
      {"rotational", ParameterShape::number, "N m s^2/rad^2", 0, inf, false, "0", "rotational drag"},
      {"centre", ParameterShape::vec3, "m", -inf, inf, false, "the CoG", "drag centre in frame c"},
  };
  k.parse = parse_air_drag;
  k.fitted_through = "drag area at the CoG and rotational drag";
  k.fit = fit_air_drag;
  return k;
}

}  // namespace rigflex::rig::kinds
