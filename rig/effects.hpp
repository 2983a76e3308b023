#pragma once
// The catalogue of physical effects, under the names of
// shared/spec/rig-conventions.md. Per-rod parameters are vectors of length n.
// How a rig file states each one and how diagnose fits it: rig/effect_kinds.hpp.
#include <memory>
#include <vector>

#include "rig/effect.hpp"

namespace rigflex::rig {

class FixedFrameFlexibility : public Effect {
 public:
  explicit FixedFrameFlexibility(FixedFrameModel m) : model_(std::move(m)) {}
  const char* name() const override { return "fixed_frame_flexibility"; }
  void validate(int rods) const override;
  void build(RigAssembly& a) const override { a.fixed_frame = model_; }
  const FixedFrameModel& model() const { return model_; }

 private:
  FixedFrameModel model_;
};

class CarryingFrameFlexibility : public Effect {
 public:
  explicit CarryingFrameFlexibility(CarryingFrameModel m) : model_(std::move(m)) {}
  const char* name() const override { return "carrying_frame_flexibility"; }
  void validate(int rods) const override;
  void build(RigAssembly& a) const override { a.carrying_frame = model_; }
  const CarryingFrameModel& model() const { return model_; }

 private:
  CarryingFrameModel model_;
};

// The frame `frame` (a built fixed or carrying frame) with its stiffness
// times `factor` > 0: K, or the carrying frame's modal stiffness, the mass
// held and the damping times sqrt(factor), which keeps every mode's damping
// ratio (a frame's damping is modal, or Rayleigh fitted to two of its modes:
// both scale so when the frequencies do). What
// diagnose refits where a frame states its stiffness's uncertainty
// (rig/effect_uncertainty.hpp). std::invalid_argument for another effect
// (a frame not yet resolved from its files is one) or a factor <= 0.
std::shared_ptr<const Effect> stiffened(const Effect& frame, double factor);

// Axial stiffness of each rod (N/m), EA/L or given; without this effect the rods are rigid.
class RodCompliance : public Effect {
 public:
  explicit RodCompliance(std::vector<double> stiffness) : k_(std::move(stiffness)) {}
  const char* name() const override { return "rod_compliance"; }
  void validate(int rods) const override;
  void build(RigAssembly& a) const override { a.rod_stiffness = k_; }

 private:
  std::vector<double> k_;
};

// Mass of each rod (kg), uniform along it: m/3 moves with each joint, m/2 of its weight hangs on each.
class RodMass : public Effect {
 public:
  explicit RodMass(std::vector<double> mass) : m_(std::move(mass)) {}
  const char* name() const override { return "rod_mass"; }
  void validate(int rods) const override;
  void build(RigAssembly& a) const override { a.rod_mass = m_; }

 private:
  std::vector<double> m_;
};

// Friction in the Hooke's joints, the same about both axes of a joint:
// torque -(c w + mu w / sqrt(|w|^2 + eps^2)) against the rod's swing rate w
// relative to the part the joint sits on.
struct JointFrictionParameters {
  double viscous = 0.0;         // c, N m s/rad
  double coulomb = 0.0;         // mu, N m
  double regularization = 1e-3; // eps, rad/s: below it Coulomb friction turns viscous (keeps the ODE smooth)
  bool upper = true, lower = true;
};
class JointFriction : public Effect {
 public:
  explicit JointFriction(JointFrictionParameters p) : p_(p) {}
  const char* name() const override { return "joint_friction"; }
  void validate(int rods) const override;
  void add_loads(const Kinematics& k, Loads& loads) const override;
  bool dissipative() const override { return true; }

 private:
  JointFrictionParameters p_;
};

// Quadratic aerodynamic drag of the body: F = -1/2 rho CdA |v| v at the drag
// centre, and a moment -c_rot |w| w.
struct AirDragParameters {
  double density = 1.2;         // kg/m^3
  double cd_area = 0.0;         // m^2, drag coefficient times frontal area
  double rotational = 0.0;      // N m s^2/rad^2
  std::optional<Vec3> centre;   // frame c; default the CoG
};
class AirDrag : public Effect {
 public:
  explicit AirDrag(AirDragParameters p) : p_(p) {}
  const char* name() const override { return "air_drag"; }
  void validate(int rods) const override;
  void add_loads(const Kinematics& k, Loads& loads) const override;
  bool dissipative() const override { return true; }

 private:
  AirDragParameters p_;
};

// Constant zero offsets of the encoders (rad), added to what they read.
class EncoderOffset : public Effect {
 public:
  EncoderOffset(std::vector<double> alpha, std::vector<double> beta) : alpha_(std::move(alpha)), beta_(std::move(beta)) {}
  const char* name() const override { return "encoder_offset"; }
  void validate(int rods) const override;
  void measure(SensorSample& s) const override;
  void unmeasure(SensorSample& s) const override;

 private:
  std::vector<double> alpha_, beta_;
};

// The true rod lengths differ from the geometry block's by delta (m).
class RodLengthError : public Effect {
 public:
  explicit RodLengthError(std::vector<double> delta) : delta_(std::move(delta)) {}
  const char* name() const override { return "rod_length_error"; }
  void validate(int rods) const override;
  void build(RigAssembly& a) const override;

 private:
  std::vector<double> delta_;
};

// The true joint centres differ from the geometry block's (m; upper in G, lower in c).
class JointPositionError : public Effect {
 public:
  JointPositionError(std::vector<Vec3> upper, std::vector<Vec3> lower) : upper_(std::move(upper)), lower_(std::move(lower)) {}
  const char* name() const override { return "joint_position_error"; }
  void validate(int rods) const override;
  void build(RigAssembly& a) const override;

 private:
  std::vector<Vec3> upper_, lower_;
};

// Load cell i reads gain_i F_i + offset_i.
class LoadCellGain : public Effect {
 public:
  LoadCellGain(std::vector<double> gain, std::vector<double> offset) : gain_(std::move(gain)), offset_(std::move(offset)) {}
  const char* name() const override { return "load_cell_gain"; }
  void validate(int rods) const override;
  void measure(SensorSample& s) const override;
  void unmeasure(SensorSample& s) const override;

 private:
  std::vector<double> gain_, offset_;
};

}  // namespace rigflex::rig
