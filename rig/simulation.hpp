#pragma once
// Time integration of the rig (CVODE's variable-order BDF with error control,
// dense Newton) and the virtual sensors that turn the motion into the
// measurement files of shared/spec/rig-conventions.md.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rig/integration.hpp"
#include "rig/linearization.hpp"
#include "rig/record.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::rig {

// A free swing from a state, sampled by a callback at every output time.
struct SwingOptions {
  double duration_s = 15.0;
  double sample_rate_hz = 500.0;
};

class Integrator {
 public:
  Integrator(const RigSystem& rig, const SimulationOptions& options);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  void reset(double t, const Configuration& c, const Velocity& v, const Push* push = nullptr);
  // Advances to t_out (interpolating, past steps allowed up to the stop time).
  void advance_to(double t_out);
  double time() const { return t_; }
  void state(Configuration& c, Velocity& v) const;
  const IntegratorStatistics& statistics() const;

  struct Impl;  // CVODE's objects; public so that the C callback can reach it

 private:
  Impl* impl_;
  double t_ = 0;
  mutable IntegratorStatistics stats_;
};

// The sensors read at one instant, before noise and quantization: the load
// cell at the upper end of the rod (the spring force plus half the rod's
// weight along it), the encoders from the rod direction about the nominal
// axes a_i; then the effects' measurement chain.
SensorSample read_sensors(const RigSystem& rig, const Configuration& c, const Velocity& v, double t);
// The same into `sample`, with `scratch` reused (no allocation once sized).
void read_sensors(const RigSystem& rig, const Configuration& c, const Velocity& v, double t, Kinematics& scratch,
                  SensorSample& sample);

// One history of the release protocol: `push` (or the given initial
// condition) from static equilibrium, then the free swing sampled at the
// sensors' rate, noise and quantization from `noise_seed`.
struct HistoryRequest {
  std::optional<Push> push;
  std::optional<InitialCondition> initial;
  double duration_s = 15.0;
  std::uint64_t noise_seed = 0;
  // At the equilibrium; for generalized-alpha (computed when absent).
  const Linearization* linearization = nullptr;
};
Record simulate_history(const RigSystem& rig, const Configuration& equilibrium, const HistoryRequest& request,
                                IntegratorStatistics* statistics = nullptr);

// Samples in a record of `duration_s` at `sample_rate_hz` (both ends
// included); std::invalid_argument past kMaxRecordSamples (a record of 8.3 h
// at 500 Hz, about 1.5 GB in memory), before any work is done.
inline constexpr double kMaxRecordSamples = 1.5e7;
Eigen::Index record_samples(double duration_s, double sample_rate_hz);

// Draws the push of history `history` of set `set` from `seed` (deterministic).
Push draw_push(const RigSystem& rig, std::uint64_t seed, int set, int history);
std::uint64_t noise_seed(std::uint64_t seed, int set, int history);

inline constexpr double kMaxHistories = 1e5;  // sets x histories in one measurement

struct MeasurementOptions {
  int sets = 1;
  int histories = 6;
  double duration_s = 15.0;
  std::uint64_t seed = 1;
  std::function<void(int set, int history)> progress;
  void validate() const;
};

// All histories of all sets: sets[k][j] is history j + 1 of set k + 1.
std::vector<std::vector<Record>> simulate_measurement(const RigSystem& rig, const MeasurementOptions& options);

}  // namespace rigflex::rig
