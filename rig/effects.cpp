#include "rig/effects.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace rigflex::rig {
namespace {

void require(bool ok, const std::string& where, const std::string& message) {
  if (!ok) throw std::invalid_argument(where + ": " + message);
}

template <class T>
void require_count(const std::vector<T>& v, int rods, const std::string& where) {
  require(static_cast<int>(v.size()) == rods, where,
          "needs one value per rod (" + std::to_string(rods) + "), got " + std::to_string(v.size()));
}

void require_finite(const std::vector<double>& v, const std::string& where) {
  for (double x : v) require(std::isfinite(x), where, "values must be finite");
}

// Friction torque against the relative swing rate w (perpendicular to the rod).
Vec3 friction_torque(const JointFrictionParameters& p, const Vec3& w) {
  return -(p.viscous * w + p.coulomb * w / std::sqrt(w.squaredNorm() + p.regularization * p.regularization));
}

}  // namespace

void FixedFrameFlexibility::validate(int rods) const {
  require_count(model_.joint_row, rods, "effects.fixed_frame_flexibility");
}

void CarryingFrameFlexibility::validate(int rods) const {
  require(model_.psi.rows() == 3 * rods, "effects.carrying_frame_flexibility", "joint rows do not match the rod count");
  require(model_.omega2.size() == model_.psi.cols() && (model_.omega2.array() > 0).all(),
          "effects.carrying_frame_flexibility", "elastic modes must have positive stiffness");
}

std::shared_ptr<const Effect> stiffened(const Effect& frame, double factor) {
  require(factor > 0 && std::isfinite(factor), frame.name(), "a stiffness factor must be positive");
  if (const auto* f = dynamic_cast<const FixedFrameFlexibility*>(&frame)) {
    FixedFrameModel m = f->model();
    m.K *= factor;
    m.C *= std::sqrt(factor);
    return std::make_shared<FixedFrameFlexibility>(std::move(m));
  }
  if (const auto* c = dynamic_cast<const CarryingFrameFlexibility*>(&frame)) {
    CarryingFrameModel m = c->model();
    m.omega2 *= factor;
    m.damping *= std::sqrt(factor);
    return std::make_shared<CarryingFrameFlexibility>(std::move(m));
  }
  throw std::invalid_argument(std::string(frame.name()) + ": not a built frame, its stiffness cannot be scaled");
}

void RodCompliance::validate(int rods) const {
  require_count(k_, rods, "effects.rod_compliance.stiffness");
  for (double k : k_) require(std::isfinite(k) && k > 0, "effects.rod_compliance.stiffness", "must be positive");
}

void RodMass::validate(int rods) const {
  require_count(m_, rods, "effects.rod_mass.mass");
  for (double m : m_) require(std::isfinite(m) && m >= 0, "effects.rod_mass.mass", "must be >= 0");
}

void JointFriction::validate(int) const {
  const std::string at = "effects.joint_friction";
  require(p_.viscous >= 0 && std::isfinite(p_.viscous), at + ".viscous", "must be >= 0");
  require(p_.coulomb >= 0 && std::isfinite(p_.coulomb), at + ".coulomb", "must be >= 0");
  require(p_.regularization > 0, at + ".regularization", "must be positive");
  require(p_.upper || p_.lower, at + ".joints", "names no joint");
}

void JointFriction::add_loads(const Kinematics& k, Loads& loads) const {
  for (size_t i = 0; i < k.rods.size(); ++i) {
    const RodKinematics& r = k.rods[i];
    const Vec3 w_rod = r.u.cross(r.u_rate);  // swing rate of the rod (the part a Hooke's joint lets through)
    Vec3 tau = Vec3::Zero();
    if (p_.upper) tau += friction_torque(p_, w_rod);  // the fixed frame's own rotation is neglected
    Vec3 tau_lower = Vec3::Zero();
    if (p_.lower) {
      const Vec3 w_rel = w_rod - (k.omega - r.u * r.u.dot(k.omega));
      tau_lower = friction_torque(p_, w_rel);
      tau += tau_lower;
    }
    // A massless rod balances the joint torques by a pair of transverse end
    // forces: l u x f = -tau.
    const Vec3 f = r.u.cross(tau) / r.length;
    loads.lower_force[i] -= f;
    loads.lower_moment[i] -= tau_lower;
    loads.upper_force[i] += f;
  }
}

void AirDrag::validate(int) const {
  const std::string at = "effects.air_drag";
  require(p_.density > 0 && std::isfinite(p_.density), at + ".density", "must be positive");
  require(p_.cd_area >= 0 && std::isfinite(p_.cd_area), at + ".cd_area", "must be >= 0");
  require(p_.rotational >= 0 && std::isfinite(p_.rotational), at + ".rotational", "must be >= 0");
  require(p_.cd_area > 0 || p_.rotational > 0, at, "needs cd_area or rotational > 0");
}

void AirDrag::add_loads(const Kinematics& k, Loads& loads) const {
  const Vec3 arm = p_.centre ? Vec3(k.R * *p_.centre) : Vec3(k.cog - k.r);
  const Vec3 v = k.v + k.omega.cross(arm);
  loads.add_body_force(-0.5 * p_.density * p_.cd_area * v.norm() * v, arm);
  loads.body_moment -= p_.rotational * k.omega.norm() * k.omega;
}

void EncoderOffset::validate(int rods) const {
  require_count(alpha_, rods, "effects.encoder_offset.alpha");
  require_count(beta_, rods, "effects.encoder_offset.beta");
  require_finite(alpha_, "effects.encoder_offset.alpha");
  require_finite(beta_, "effects.encoder_offset.beta");
}

void EncoderOffset::measure(SensorSample& s) const {
  for (size_t i = 0; i < alpha_.size(); ++i) {
    s.alpha(i) += alpha_[i];
    s.beta(i) += beta_[i];
  }
}

void EncoderOffset::unmeasure(SensorSample& s) const {
  for (size_t i = 0; i < alpha_.size(); ++i) {
    s.alpha(i) -= alpha_[i];
    s.beta(i) -= beta_[i];
  }
}

void RodLengthError::validate(int rods) const {
  require_count(delta_, rods, "effects.rod_length_error.delta");
  require_finite(delta_, "effects.rod_length_error.delta");
}

void RodLengthError::build(RigAssembly& a) const {
  for (size_t i = 0; i < delta_.size(); ++i) a.geometry.rods[i].length += delta_[i];
}

void JointPositionError::validate(int rods) const {
  require_count(upper_, rods, "effects.joint_position_error.upper");
  require_count(lower_, rods, "effects.joint_position_error.lower");
}

void JointPositionError::build(RigAssembly& a) const {
  for (size_t i = 0; i < upper_.size(); ++i) {
    a.geometry.rods[i].upper += upper_[i];
    a.geometry.rods[i].lower += lower_[i];
  }
}

void LoadCellGain::validate(int rods) const {
  require_count(gain_, rods, "effects.load_cell_gain.gain");
  require_count(offset_, rods, "effects.load_cell_gain.offset");
  for (double g : gain_) require(std::isfinite(g) && g > 0, "effects.load_cell_gain.gain", "must be positive");
  require_finite(offset_, "effects.load_cell_gain.offset");
}

void LoadCellGain::measure(SensorSample& s) const {
  for (size_t i = 0; i < gain_.size(); ++i) s.force(i) = gain_[i] * s.force(i) + offset_[i];
}

void LoadCellGain::unmeasure(SensorSample& s) const {
  for (size_t i = 0; i < gain_.size(); ++i) s.force(i) = (s.force(i) - offset_[i]) / gain_[i];
}

}  // namespace rigflex::rig
