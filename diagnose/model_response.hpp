#pragma once
// What the rig model predicts the sensors read during a free swing that
// starts from a given swing state: the forward half of model-vs-measurement
// comparison (diagnose/history_comparison.hpp) and of effect fitting (diagnose/diagnosis.hpp).
//
// The swing state is six numbers at the record's first sample, relative to
// the static equilibrium, all in G: P's horizontal displacement (x, y), the
// yaw, P's horizontal velocity and the yaw rate. Everything else follows
// from the rig: the other pose coordinates and the frames settle statically
// with those three held (as an operator holds the body), and the vertical
// velocity and the roll and pitch rates are those that keep every rod's
// length (the rods are stiff: a stretch rate left in would ring the rods'
// 100-300 Hz bounce at kilonewtons). Six numbers, not the full state, is
// what a free swing of a multi-filar pendulum can be fitted by without
// exciting modes no sensor shows.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rig/linearization.hpp"
#include "rig/rig_system.hpp"
#include "rig/simulation.hpp"

namespace rigflex::diagnose {

using SwingState = Eigen::Matrix<double, 6, 1>;  // x, y (m), yaw (rad), vx, vy (m/s), yaw rate (rad/s)

// The rig's deformation modes up to the integrator's resolved frequency
// (ResponseModel::elastic_modes), at the record's first sample: modal
// amplitudes and rates of the M-normalized shapes. A release leaves the
// frames ringing (examples/large-rig at 4.8 Hz, 2 % damping, for seconds);
// a model that has those modes follows the ringing only from its initial
// state. Empty: the frames start settled.
struct ElasticState {
  Eigen::VectorXd amplitude, rate;
  bool empty() const { return amplitude.size() == 0; }
};

// Sensor channels as one matrix, samples x 3n: F1..Fn, alpha1..alphan, beta1..betan.
std::vector<std::string> channel_names(int rods);
Eigen::MatrixXd channels_of(const rig::Record& h);

// A rig model ready to predict: the assembled system and its linearization
// (the static equilibrium and the generalized-alpha iteration matrix).
struct ResponseModel {
  explicit ResponseModel(const rig::RigModel& model);  // NoEquilibrium, std::invalid_argument
  rig::RigSystem system;
  rig::Linearization linearization;
  // Frequency up to which the integrator resolves the modes (rig/generalized_alpha.hpp):
  // the swing modes and the first deformation mode, capped at kResolveCapHz.
  // A stiffer deformation mode acts quasi-statically in the swing band, and
  // the implicit integrator gets its static part right unresolved; an
  // uncapped very stiff fitted compliance would shrink the step without end.
  double resolve_hz = 0;
  static constexpr double kResolveCapHz = 20.0;
  std::vector<int> elastic_modes;  // indices into linearization.modes: deformation modes <= resolve_hz
};

// The lowest swing mode's frequency (Hz); 0 when the model has none.
double lowest_swing_hz(const ResponseModel& m);

// The full rig state (configuration and velocity) of a swing state.
void swing_initial_state(const ResponseModel& m, const SwingState& s, rig::Configuration& c, rig::Velocity& v,
                         const ElasticState& elastic = {});

// Noise-free sensor readings (channels_of layout) at the times t, the swing
// starting from `s` at t(0). Generalized-alpha with the step the model's
// modes need for the record's median sample interval.
Eigen::MatrixXd predict_channels(const ResponseModel& m, const SwingState& s, const Eigen::VectorXd& t,
                                 const ElasticState& elastic = {});

// A first estimate of the swing state from the encoders alone: rod
// directions -> lower joints -> pose fit over the first `window_s`, a
// quadratic in time per coordinate, its value and slope at t(0).
SwingState swing_state_from_encoders(const ResponseModel& m, const Eigen::VectorXd& t, const Eigen::MatrixXd& channels,
                                     double window_s = 0.4);

}  // namespace rigflex::diagnose
