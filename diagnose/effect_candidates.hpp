#pragma once
// The catalogue's effects as `rigflex diagnose` fits them: each effect of
// shared/spec/rig-conventions.md with a small set of parameters, a probe
// size for the finite-difference sensitivities (an effect clearly visible
// in the swing yet in its linear range), the range in which a value is
// physically plausible, the rig-file block that adds the fitted effect, and
// what to add to the model to capture it properly.
//
// Parameterizations (why these, docs/compare.md):
//   fixed_frame_flexibility    compliance of each upper joint along x, y, z and of the frame's top (sway x, y; twist)
//   carrying_frame_flexibility compliance of the lower joints, as one plate, against the body (x, y, z; rocking x, y)
//   rod_compliance             one axial compliance for all rods
//   rod_mass                   one mass for all rods
//   joint_friction             viscous and Coulomb torque, both joints of every rod
//   air_drag                   quadratic drag area at the CoG and rotational drag
//   encoder_offset             offset of every encoder angle
//   rod_length_error           length error of every rod
//   joint_position_error       position error of every upper joint (its vertical part is a rod length error)
//   load_cell_gain             gain and offset of every load cell
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rig/effect.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::diagnose {

// What the parameterizations are scaled by: the rig being diagnosed.
struct CandidateContext {
  rig::RigGeometry geometry;        // as assembled (geometry errors the model has included)
  double suspended_mass = 0;   // kg, body and the rods' moving shares
  double body_mass = 0;        // kg: what a rig file's joint-compliance frame takes (io/rig_reader)
  double weight_per_rod = 0;   // N
  double rod_length = 0;       // mean, m
  double swing_omega = 0;      // rad/s, lowest swing mode
  double joint_radius = 0;     // RMS distance of the lower joints from their centroid, m
  int rods = 0;
};
CandidateContext candidate_context(const rig::RigSystem& rig, double lowest_swing_hz);

struct CandidateParameter {
  std::string name, unit;
  double probe = 0;              // finite-difference step
  double low = 0, high = 0;      // plausible values
  bool non_negative = false;     // the effect cannot be built with a negative value
};

struct EffectCandidate {
  std::string effect;                               // the spec's name
  std::vector<CandidateParameter> parameters;
  // The effect with these parameter values (non-negative ones clamped at 0);
  // nullptr when the values amount to no effect (a compliance of zero).
  std::function<std::shared_ptr<const rig::Effect>(const Eigen::VectorXd&)> make;
  // Rig-file block (YAML, under `effects:`) that adds the effect with these values.
  std::function<std::string(const Eigen::VectorXd&)> rig_block;
  std::string advice;                               // what to add to capture it properly
};

// Every effect of the catalogue, in the spec's order.
std::vector<EffectCandidate> effect_candidates(const CandidateContext& context);

}  // namespace rigflex::diagnose
