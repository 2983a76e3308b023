#include "diagnose/effect_candidates.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "rig/effects.hpp"
#include "rig/joint_compliance.hpp"

namespace rigflex::diagnose {
namespace {

std::string num(double x) {
  std::ostringstream s;
  s << std::setprecision(6) << x;
  return s.str();
}

std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + num(v[i]);
  return s + "]";
}

std::vector<double> segment(const Eigen::VectorXd& x, int first, int count) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i) v.push_back(x(first + i));
  return v;
}

double positive(double x) { return std::max(x, 0.0); }

std::vector<CandidateParameter> per_rod(const std::string& prefix, const std::string& unit, int n, double probe,
                                        double bound) {
  std::vector<CandidateParameter> p;
  for (int i = 1; i <= n; ++i) p.push_back({prefix + std::to_string(i), unit, probe, -bound, bound, false});
  return p;
}

}  // namespace

CandidateContext candidate_context(const rig::RigSystem& rig, double lowest_swing_hz) {
  CandidateContext c;
  c.geometry = rig.assembly().geometry;
  c.rods = rig.rods();
  c.suspended_mass = rig.suspended_mass();
  c.body_mass = rig.assembly().body.mass;
  c.weight_per_rod = rig.suspended_weight() / c.rods;
  rig::Vec3 centroid = rig::Vec3::Zero();
  for (const auto& r : c.geometry.rods) {
    c.rod_length += r.length / c.rods;
    centroid += r.lower / c.rods;
  }
  for (const auto& r : c.geometry.rods) c.joint_radius += (r.lower - centroid).squaredNorm() / c.rods;
  c.joint_radius = std::sqrt(c.joint_radius);
  c.swing_omega = 2.0 * 3.141592653589793 * (lowest_swing_hz > 0 ? lowest_swing_hz : 0.5);
  return c;
}

std::vector<EffectCandidate> effect_candidates(const CandidateContext& x) {
  const int n = x.rods;
  const double W = x.weight_per_rod, L = x.rod_length, M = x.suspended_mass, w = x.swing_omega;
  const double rho = std::max(x.joint_radius, 0.1 * L);
  // Compliances: probe 0.5 mm under a rod's static load; plausible up to
  // 50 mm under it (vertical), or 1 m under it (frames sideways: they carry
  // only the swing's horizontal loads, a few % of it).
  const double c_probe = 5e-4 / W, c_high = 5e-2 / W, c_side = 1.0 / W;
  std::vector<EffectCandidate> out;

  {
    EffectCandidate e;
    e.effect = "fixed_frame_flexibility";
    for (int i = 1; i <= n; ++i) {
      for (const char* a : {"x", "y", "z"}) {
        e.parameters.push_back({"joint" + std::to_string(i) + "_" + a + "_compliance", "m/N", c_probe, 0,
                                std::string(a) == "z" ? c_high : c_side, true});
      }
    }
    e.parameters.push_back({"sway_x_compliance", "m/N", c_probe / n, 0, c_side, true});
    e.parameters.push_back({"sway_y_compliance", "m/N", c_probe / n, 0, c_side, true});
    e.parameters.push_back({"twist_compliance", "rad/(N m)", c_probe / (n * rho * rho), 0, c_side / (rho * rho), true});
    auto fixed = [n](const Eigen::VectorXd& p) {
      rig::FixedJointCompliance f;
      for (int i = 0; i < n; ++i) f.joints.push_back(p.segment<3>(3 * i).cwiseMax(0.0));
      f.sway = p.segment<2>(3 * n).cwiseMax(0.0);
      f.twist = positive(p(3 * n + 2));
      return f;
    };
    e.make = [x, c_probe, rho, fixed, n](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      Eigen::VectorXd size = p.cwiseMax(0.0);
      size(3 * n + 2) *= rho * rho;
      if (size.maxCoeff() < 1e-2 * c_probe) return nullptr;
      return std::make_shared<rig::FixedFrameFlexibility>(joint_compliance_fixed_frame(x.geometry, x.body_mass, fixed(p)));
    };
    e.rig_block = [fixed](const Eigen::VectorXd& p) {
      const rig::FixedJointCompliance f = fixed(p);
      std::string s = "fixed_frame_flexibility:\n  joint_compliance:\n    joints: [";
      for (size_t i = 0; i < f.joints.size(); ++i) {
        s += (i ? ", " : "") + list({f.joints[i].x(), f.joints[i].y(), f.joints[i].z()});
      }
      return s + "]\n    sway: " + list({f.sway.x(), f.sway.y()}) + "\n    twist: " + num(f.twist) + "\n";
    };
    e.advice = "model the fixed frame with finite elements and reduce it onto the upper joints "
               "(effects.fixed_frame_flexibility.model, or a `rigflex reduce` export); the fitted joint compliance "
               "is a stand-in that captures its quasi-static part";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "carrying_frame_flexibility";
    e.parameters = {{"x_compliance", "m/N", c_probe, 0, c_side, true},
                    {"y_compliance", "m/N", c_probe, 0, c_side, true},
                    {"z_compliance", "m/N", c_probe, 0, c_high, true},
                    {"rocking_x_compliance", "rad/(N m)", c_probe / (rho * rho), 0, c_side / (rho * rho), true},
                    {"rocking_y_compliance", "rad/(N m)", c_probe / (rho * rho), 0, c_side / (rho * rho), true}};
    auto carrying = [](const Eigen::VectorXd& p) {
      rig::CarryingJointCompliance c;
      c.translation = p.head<3>().cwiseMax(0.0);
      c.rocking = p.segment<2>(3).cwiseMax(0.0);
      return c;
    };
    e.make = [x, c_probe, rho, carrying](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      Eigen::VectorXd size = p.cwiseMax(0.0);
      size.tail<2>() *= rho * rho;
      if (size.maxCoeff() < 1e-2 * c_probe) return nullptr;
      return std::make_shared<rig::CarryingFrameFlexibility>(
          joint_compliance_carrying_frame(x.geometry, x.body_mass, carrying(p)));
    };
    e.rig_block = [carrying](const Eigen::VectorXd& p) {
      const rig::CarryingJointCompliance c = carrying(p);
      return "carrying_frame_flexibility:\n  joint_compliance:\n    translation: " +
             list({c.translation.x(), c.translation.y(), c.translation.z()}) +
             "\n    rocking: " + list({c.rocking.x(), c.rocking.y()}) + "\n";
    };
    e.advice = "model the carrying frame with finite elements and reduce it free-free onto the lower joints "
               "(effects.carrying_frame_flexibility.model); the fitted plate compliance is a stand-in";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "rod_compliance";
    e.parameters = {{"axial_compliance", "m/N", c_probe, 0, c_high, true}};
    // Below 1 % of the probe (5 um under the static load) the rods are as
    // stiff as the rigid rods' realization: no effect.
    e.make = [n, c_probe](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      if (p(0) < 1e-2 * c_probe) return nullptr;
      return std::make_shared<rig::RodCompliance>(std::vector<double>(n, 1.0 / p(0)));
    };
    e.rig_block = [](const Eigen::VectorXd& p) {
      return "rod_compliance: {stiffness: " + num(1.0 / std::max(p(0), 1e-15)) + "}\n";
    };
    e.advice = "give the rods' axial stiffness (effects.rod_compliance: youngs_modulus and area, or stiffness)";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "rod_mass";
    e.parameters = {{"mass", "kg", 0.01 * M / n, 0, 0.1 * M / n, true}};
    e.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      return std::make_shared<rig::RodMass>(std::vector<double>(n, positive(p(0))));
    };
    e.rig_block = [](const Eigen::VectorXd& p) { return "rod_mass: {mass: " + num(positive(p(0))) + "}\n"; };
    e.advice = "weigh a rod and give its mass (effects.rod_mass.mass)";
    out.push_back(e);
  }
  {
    // A damping ratio of about 1e-3 of the swing from the viscous probe; the
    // Coulomb probe dissipates about as much at 0.02 rad of swing.
    const double viscous = 2e-3 * M * L * L * w / (2.0 * n);
    EffectCandidate e;
    e.effect = "joint_friction";
    e.parameters = {{"viscous", "N m s/rad", viscous, 0, 1000 * viscous, true},
                    {"coulomb", "N m", viscous * 0.02 * w, 0, 1000 * viscous * 0.02 * w, true}};
    e.make = [](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      rig::JointFrictionParameters f;
      f.viscous = positive(p(0));
      f.coulomb = positive(p(1));
      if (f.viscous <= 0 && f.coulomb <= 0) return nullptr;
      return std::make_shared<rig::JointFriction>(f);
    };
    e.rig_block = [](const Eigen::VectorXd& p) {
      return "joint_friction: {viscous: " + num(positive(p(0))) + ", coulomb: " + num(positive(p(1))) + "}\n";
    };
    e.advice = "add joint friction (effects.joint_friction), or service the Hooke's joints' bearings";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "air_drag";
    // Drag is linear in both parameters; the probes damp the swing by a
    // ratio of about 1e-3 at 0.05 rad of swing (far above the integrator's
    // rounding) and are no statement of what is plausible.
    const double rotational = 0.02 * M * rho * rho;
    e.parameters = {{"cd_area", "m^2", 0.08 * M / L, 0, 30.0, true},
                    {"rotational", "N m s^2/rad^2", rotational, 0, 1e3 * rotational, true}};
    e.make = [](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      rig::AirDragParameters d;
      d.cd_area = positive(p(0));
      d.rotational = positive(p(1));
      if (d.cd_area <= 0 && d.rotational <= 0) return nullptr;
      return std::make_shared<rig::AirDrag>(d);
    };
    e.rig_block = [](const Eigen::VectorXd& p) {
      return "air_drag: {cd_area: " + num(positive(p(0))) + ", rotational: " + num(positive(p(1))) + "}\n";
    };
    e.advice = "add air drag (effects.air_drag: the body's drag area), or shield the body from drafts";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "encoder_offset";
    e.parameters = per_rod("alpha", "rad", n, 1e-3, 0.05);
    const auto beta = per_rod("beta", "rad", n, 1e-3, 0.05);
    e.parameters.insert(e.parameters.end(), beta.begin(), beta.end());
    e.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      return std::make_shared<rig::EncoderOffset>(segment(p, 0, n), segment(p, n, n));
    };
    e.rig_block = [n](const Eigen::VectorXd& p) {
      return "encoder_offset: {alpha: " + list(segment(p, 0, n)) + ", beta: " + list(segment(p, n, n)) + "}\n";
    };
    e.advice = "calibrate the encoders' zero with the rods hanging at rest and give the offsets "
               "(effects.encoder_offset)";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "rod_length_error";
    e.parameters = per_rod("delta", "m", n, 1e-3, 0.05 * L);
    e.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      return std::make_shared<rig::RodLengthError>(segment(p, 0, n));
    };
    e.rig_block = [n](const Eigen::VectorXd& p) { return "rod_length_error: {delta: " + list(segment(p, 0, n)) + "}\n"; };
    e.advice = "measure the rods' joint-to-joint lengths and correct geometry.rods[*].length";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "joint_position_error";
    for (int i = 1; i <= n; ++i) {
      for (const char* a : {"x", "y", "z"}) {
        e.parameters.push_back({"upper" + std::to_string(i) + "_" + a, "m", 1e-3, -0.05, 0.05, false});
      }
    }
    e.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      std::vector<rig::Vec3> upper, lower(static_cast<size_t>(n), rig::Vec3::Zero());
      for (int i = 0; i < n; ++i) upper.push_back(p.segment<3>(3 * i));
      return std::make_shared<rig::JointPositionError>(upper, lower);
    };
    e.rig_block = [n](const Eigen::VectorXd& p) {
      std::string s = "joint_position_error:\n  upper: [";
      for (int i = 0; i < n; ++i) s += (i ? ", " : "") + list(segment(p, 3 * i, 3));
      return s + "]\n";
    };
    e.advice = "survey the joint centres and correct geometry.rods[*].upper and lower";
    out.push_back(e);
  }
  {
    EffectCandidate e;
    e.effect = "load_cell_gain";
    e.parameters = per_rod("gain_error", "1", n, 1e-3, 0.1);
    const auto offset = per_rod("offset", "N", n, 1e-3 * W, 0.1 * W);
    e.parameters.insert(e.parameters.end(), offset.begin(), offset.end());
    e.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const rig::Effect> {
      std::vector<double> gain = segment(p, 0, n);
      for (double& g : gain) g = std::max(1.0 + g, 1e-3);
      return std::make_shared<rig::LoadCellGain>(gain, segment(p, n, n));
    };
    e.rig_block = [n](const Eigen::VectorXd& p) {
      std::vector<double> gain = segment(p, 0, n);
      for (double& g : gain) g = 1.0 + g;
      return "load_cell_gain: {gain: " + list(gain) + ", offset: " + list(segment(p, n, n)) + "}\n";
    };
    e.advice = "calibrate the load cells against known weights and give gain and offset (effects.load_cell_gain)";
    out.push_back(e);
  }
  return out;
}

}  // namespace rigflex::diagnose
