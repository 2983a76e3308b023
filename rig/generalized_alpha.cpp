#include "rig/generalized_alpha.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rig/equilibrium.hpp"

namespace rigflex::rig {
namespace {

constexpr double kRhoInfinity = 0.8;
constexpr int kMaxIterations = 8;
constexpr int kMaxRefreshes = 3;  // per step
constexpr int kMaxHalvings = 6;  // shortest step: h / 2^6

Eigen::VectorXd to_vector(const Velocity& v) {
  Eigen::VectorXd x(6 + v.eta.size() + v.xf.size());
  x << v.V, v.w, v.eta, v.xf;
  return x;
}

void fill_velocity(const Eigen::VectorXd& x, Eigen::Index ne, Eigen::Index nf, Velocity& v) {
  v.V = x.segment<3>(0);
  v.w = x.segment<3>(3);
  v.eta = x.segment(6, ne);
  v.xf = x.segment(6 + ne, nf);
}

Velocity to_velocity(const Eigen::VectorXd& x, Eigen::Index ne, Eigen::Index nf) {
  Velocity v;
  fill_velocity(x, ne, nf, v);
  return v;
}

// -dQ/dv at (c, v) (frame damping, the friction laws' slopes), by central
// differences.
Eigen::MatrixXd damping_tangent(const RigSystem& rig, const Configuration& c, const Eigen::VectorXd& v) {
  const int n = rig.coordinate_count();
  const Eigen::VectorXd steps = coordinate_steps(rig);
  Eigen::MatrixXd C(n, n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd dv = Eigen::VectorXd::Zero(n);
    dv(j) = steps(j);  // 1e-6 L per second at the joints
    const Eigen::VectorXd Qp = rig.generalized_forces(c, to_velocity(v + dv, rig.elastic_modes(), rig.fixed_dofs()), 0.0);
    const Eigen::VectorXd Qm = rig.generalized_forces(c, to_velocity(v - dv, rig.elastic_modes(), rig.fixed_dofs()), 0.0);
    C.col(j) = -(Qp - Qm) / (2.0 * steps(j));
  }
  return C;
}

}  // namespace

double generalized_alpha_step(const Linearization& lin, double sample_rate_hz, double resolve_hz) {
  if (!(sample_rate_hz > 0)) throw std::invalid_argument("generalized_alpha_step: sample rate must be positive");
  double f = resolve_hz;
  bool deformation_seen = false;
  for (const RigMode& m : lin.modes) {
    if (m.kind == RigModeKind::swing) f = std::max(f, m.frequency_hz);
    if (m.kind == RigModeKind::deformation && !deformation_seen && resolve_hz == 0) {
      f = std::max(f, m.frequency_hz);
      deformation_seen = true;
    }
  }
  const double dt = 1.0 / sample_rate_hz;
  if (f <= 0) return dt;
  // The swing itself needs far finer steps than 30 per period: its period
  // error, about (omega h)^2 / 18 here, accumulates over a record of some
  // ten periods into a phase the fits read as a rod length (measured:
  // records at 100 Hz of a rigid trifilar swinging at 0.58 Hz got 10 ms
  // steps, a period error of 7.5e-5 and 15-28 x the noise against records
  // integrated by BDF: a rod length error of 0.15 mm named on clean data).
  // No step is longer than kMaxStep, what records at 500 Hz give a rig with
  // rigid frames, which reaches the noise: a period error below 9e-6 for
  // swings up to 1 Hz.
  const double k = std::max(std::ceil(dt * 30.0 * f - 1e-9), std::ceil(dt / kMaxStep - 1e-9));
  return dt / std::max(1.0, k);
}

GeneralizedAlpha::GeneralizedAlpha(const RigSystem& rig, const Linearization& lin, double step_s,
                                   double position_tolerance)
    : rig_(rig), h_(step_s), tolerance_(position_tolerance) {
  if (!(step_s > 0)) throw std::invalid_argument("generalized-alpha: step must be positive");
  if (!(position_tolerance > 0)) throw std::invalid_argument("generalized-alpha: tolerance must be positive");
  const double r = kRhoInfinity;
  alpha_m_ = (2.0 * r - 1.0) / (r + 1.0);
  alpha_f_ = r / (r + 1.0);
  gamma_ = 0.5 + alpha_f_ - alpha_m_;
  beta_ = 0.25 * (gamma_ + 0.5) * (gamma_ + 0.5);
  M_ = lin.M;
  K_ = lin.K;
  C_ = damping_tangent(rig, lin.equilibrium.configuration, Eigen::VectorXd::Zero(rig.coordinate_count()));
  const Eigen::VectorXd steps = coordinate_steps(rig);
  joint_scale_ = steps / steps(0);
  factorize(h_, K_);
}

void GeneralizedAlpha::factorize(double h, const Eigen::MatrixXd& K) {
  // d(residual)/d(vdot_{n+1}), multiplied by M: M + h gamma c C + h^2 beta c K.
  const double c = (1.0 - alpha_f_) / (1.0 - alpha_m_);
  S_.compute(M_ + h * gamma_ * c * C_ + h * h * beta_ * c * K);
  S_step_ = h;
  ++stats_.linear_setups;
}

Eigen::VectorXd GeneralizedAlpha::accelerations(const Configuration& c, const Eigen::VectorXd& v, double t) {
  ++stats_.rhs_evaluations;
  const Velocity vel = to_velocity(v, rig_.elastic_modes(), rig_.fixed_dofs());
  ExternalLoad load;
  return rig_.accelerations(vel, rig_.generalized_forces(c, vel, t, push_ ? push_->load_at(t, load) : nullptr));
}

void GeneralizedAlpha::force_residual(const Configuration& c, const Eigen::VectorXd& v, const Eigen::VectorXd& vdot,
                                      double t) {
  ++stats_.rhs_evaluations;
  fill_velocity(v, rig_.elastic_modes(), rig_.fixed_dofs(), velocity_);
  ExternalLoad load;
  rig_.generalized_forces(c, velocity_, t, push_ ? push_->load_at(t, load) : nullptr, work_, Q_);
  rig_.subtract_gyroscopic(velocity_, Q_);
  residual_.noalias() = M_ * vdot;
  residual_ -= Q_;
}

void GeneralizedAlpha::refresh_tangents(const Configuration& c, const Eigen::VectorXd& v, double t) {
  // Forward differences (half the evaluations of central ones): an
  // iteration matrix needs a few digits, not the linearization's eight.
  const int n = rig_.coordinate_count();
  const Eigen::VectorXd steps = coordinate_steps(rig_);
  const Eigen::VectorXd vdot = Eigen::VectorXd::Zero(n);
  force_residual(c, v, vdot, t);
  const Eigen::VectorXd base = residual_;  // = -(Q - gyroscopic)
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
  Configuration moved;
  for (int j = 0; j < n; ++j) {
    s(j) = steps(j);
    rig_.displaced(c, s, moved);
    force_residual(moved, v, vdot, t);
    K_.col(j) = (residual_ - base) / steps(j);
    s(j) = 0.0;
  }
  K_ = (0.5 * (K_ + K_.transpose())).eval();
  // Without dissipative effects (friction, drag) or rod dampers (c u u',
  // turning with the rods like their stiffness) the damping is linear and C
  // stays as built (the gyroscopic terms it leaves out weigh ~1e-4 of M in
  // the iteration matrix at swing speeds).
  const auto& effects = rig_.model().effects;
  if (std::none_of(effects.begin(), effects.end(), [](const auto& e) { return e->dissipative(); }) &&
      rig_.rod_damping().isZero(0.0)) {
    return;
  }
  C_ = damping_tangent(rig_, c, v);
}

void GeneralizedAlpha::reset(double t, const Configuration& c, const Velocity& v, const Push* push) {
  t_ = t;
  c_ = c;
  v_ = to_vector(v);
  push_ = push ? std::optional<Push>(*push) : std::nullopt;
  vdot_ = accelerations(c_, v_, t_);
  vdot_previous_ = vdot_;
  a_ = vdot_;
}

void GeneralizedAlpha::advance_to(double t_out) {
  // Times within 1e-9 h of the grid are on it: no sliver steps (each would
  // refactorize the iteration matrix) from rounding in the sample times.
  const double snap = 1e-9 * h_;
  while (t_ < t_out - snap) {
    const double left = t_out - t_;
    step(left > h_ + snap ? h_ : left < h_ - snap ? left : h_);
    if (std::abs(t_ - t_out) <= snap) t_ = t_out;
  }
}

void GeneralizedAlpha::step(double h, int halvings) {
  // A step whose Newton iterations do not converge is taken again as two
  // halves: a light joint on a stiff rod, started away from its quasi-static
  // place (a fitted elastic state, a probe of one), moves by millimetres in
  // the first step, far outside the tangent the iterations start from; a
  // shorter step keeps the predictor near the answer. The state is only
  // committed by a converged step.
  if (try_step(h)) return;
  if (halvings == kMaxHalvings) {
    throw IntegrationFailure("generalized-alpha", t_ + h,
                             "Newton iterations did not converge, even with the step halved " +
                                 std::to_string(kMaxHalvings) + " times");
  }
  ++stats_.halvings;
  // The failed iterations left the tangent of a state far off: take it anew here.
  refresh_tangents(c_, v_, t_);
  step(0.5 * h, halvings + 1);
  step(0.5 * h, halvings + 1);
}

bool GeneralizedAlpha::try_step(double h) {
  if (h != S_step_) factorize(h, K_);
  const double c = (1.0 - alpha_f_) / (1.0 - alpha_m_);
  const double t1 = t_ + h;
  // Predictor: the acceleration extrapolated linearly from the last two steps.
  Eigen::VectorXd vd = vdot_ + (h / h_last_) * (vdot_ - vdot_previous_);
  // c1, v1, a1: the state at t + h that the current vd implies.
  Configuration& c1 = trial_;
  Eigen::VectorXd& a1 = a1_;
  Eigen::VectorXd& v1 = v1_;
  auto update = [&] {
    a1 = (alpha_f_ * vdot_ + (1.0 - alpha_f_) * vd - alpha_m_ * a_) / (1.0 - alpha_m_);
    v1 = v_ + h * ((1.0 - gamma_) * a_ + gamma_ * a1);
    increment_ = h * (v_ + h * ((0.5 - beta_) * a_ + beta_ * a1));
    rig_.displaced(c_, increment_, c1);
  };
  // Modified Newton: the iteration matrix is kept while it contracts by 10x
  // per iteration and refreshed at the current state when it does not: the
  // rods turn with the swing and their axial stiffness k u u' turns with
  // them (a 0.05 rad swing puts a 10 % error on the stiffest entries).
  int refreshes = 0;
  double previous = HUGE_VAL;
  for (int it = 0;; ++it) {
    update();
    force_residual(c1, v1, vd, t1);
    delta_ = S_.solve(residual_);
    vd -= delta_;
    ++stats_.newton_iterations;
    // Converged when the correction moves no joint by more than the tolerance.
    const double moved = h * h * beta_ * c * delta_.cwiseProduct(joint_scale_).cwiseAbs().maxCoeff();
    if (moved <= tolerance_) break;
    const bool slow = it >= 1 && moved > 0.1 * previous;
    previous = moved;
    if (slow || it + 1 == kMaxIterations) {
      if (refreshes == kMaxRefreshes) return false;
      update();
      refresh_tangents(c1, v1, t1);
      factorize(h, K_);
      ++refreshes;
      previous = HUGE_VAL;
      it = -1;
    }
  }
  update();
  t_ = t1;
  c_ = c1;
  v_ = v1;
  vdot_previous_ = vdot_;
  h_last_ = h;
  vdot_ = vd;
  a_ = a1;
  ++stats_.steps;
  return true;
}

void GeneralizedAlpha::state(Configuration& c, Velocity& v) const {
  c = c_;
  v = to_velocity(v_, rig_.elastic_modes(), rig_.fixed_dofs());
}

}  // namespace rigflex::rig
