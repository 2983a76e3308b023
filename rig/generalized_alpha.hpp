#pragma once
// Generalized-alpha (Chung and Hulbert 1993) on the rig's configuration
// space, SE(3) x R^n (Arnold and Bruls 2007: the increment is applied by
// SE(3)'s exponential, RigSystem::displaced), with a fixed step and modified
// Newton iterations on a constant iteration matrix from the linearization at
// the static equilibrium.
//
// Why a fixed step and not CVODE's BDF: the undamped rod and frame
// vibrations (80-900 Hz) make BDF orders 3-5 unstable unless every step
// resolves them, and BDF2 needs ~20000 steps per 15 s for a 1e-5 frequency
// error. Generalized-alpha is second order, unconditionally stable, damps
// the unresolved high frequencies (spectral radius rho_inf = 0.8 at
// omega h -> infinity) and keeps the period error of the resolved ones
// below (omega h)^2 / 6 (tests/rig: against a tight BDF run). The step
// (generalized_alpha_step) gives every mode up to the first deformation mode
// at least 30 steps per period (period error <= 0.7 % there; ~1e-5 on the
// swing of examples/large-rig at 2 ms), is at most 2 ms whatever the sample
// rate (the swing's period error below 9e-6 up to 1 Hz), and divides the
// sample interval, so samples are steps, not interpolations.
#include <Eigen/Core>
#include <Eigen/LU>
#include <optional>

#include "rig/integration.hpp"
#include "rig/linearization.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::rig {

// Largest step <= 1 / (30 f) for every swing mode and the first deformation
// mode of `lin` (or, resolve_hz > 0, for every frequency up to resolve_hz),
// and <= kMaxStep (the swing's accuracy, generalized_alpha.cpp), that
// divides 1 / sample_rate_hz.
inline constexpr double kMaxStep = 2e-3;  // s
double generalized_alpha_step(const Linearization& lin, double sample_rate_hz, double resolve_hz = 0.0);

class GeneralizedAlpha {
 public:
  // `lin` at the static equilibrium gives the iteration matrix; step_s > 0.
  GeneralizedAlpha(const RigSystem& rig, const Linearization& lin, double step_s, double position_tolerance);

  void reset(double t, const Configuration& c, const Velocity& v, const Push* push = nullptr);
  // Steps to t_out (a last, shorter step if t_out is not on the step grid).
  void advance_to(double t_out);
  double time() const { return t_; }
  void state(Configuration& c, Velocity& v) const;
  const IntegratorStatistics& statistics() const { return stats_; }

 private:
  void step(double h, int halvings = 0);  // halvings: how often h was already halved
  bool try_step(double h);  // false: Newton did not converge; nothing committed
  void factorize(double h, const Eigen::MatrixXd& K);
  Eigen::VectorXd accelerations(const Configuration& c, const Eigen::VectorXd& v, double t);
  // M vdot - (Q - gyroscopic terms) at (c, v, t), into residual_.
  void refresh_tangents(const Configuration& c, const Eigen::VectorXd& v, double t);
  void force_residual(const Configuration& c, const Eigen::VectorXd& v, const Eigen::VectorXd& vdot, double t);

  const RigSystem& rig_;
  double h_, tolerance_;
  double alpha_m_, alpha_f_, gamma_, beta_;
  Eigen::MatrixXd M_, C_, K_;
  Eigen::PartialPivLU<Eigen::MatrixXd> S_;
  double S_step_ = 0;
  Eigen::VectorXd joint_scale_;  // joint displacement per unit of each coordinate
  double t_ = 0;
  Configuration c_;
  Eigen::VectorXd v_, vdot_, a_, vdot_previous_;
  double h_last_ = 1.0;
  std::optional<Push> push_;
  IntegratorStatistics stats_;
  // Scratch of the Newton iterations, sized once.
  RigSystem::Workspace work_;
  Velocity velocity_;
  Configuration trial_;
  Eigen::VectorXd Q_, residual_, delta_, increment_, a1_, v1_;
};

}  // namespace rigflex::rig
