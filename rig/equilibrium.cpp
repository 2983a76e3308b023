#include "rig/equilibrium.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rigflex::rig {
namespace {

double mean_rod_length(const RigSystem& rig) {
  double L = 0;
  for (const auto& r : rig.assembly().geometry.rods) L += r.length;
  return L / rig.rods();
}

// Largest joint displacement per unit of each carrying-frame modal coordinate.
Eigen::VectorXd modal_reach(const RigSystem& rig) {
  if (!rig.elastic_modes()) return {};
  return rig.assembly().carrying_frame->psi.cwiseAbs().colwise().maxCoeff().transpose();
}

Eigen::VectorXd remove_held(const Eigen::VectorXd& v, const std::vector<bool>& held) {
  Eigen::VectorXd out(std::count(held.begin(), held.end(), false));
  for (Eigen::Index i = 0, k = 0; i < v.size(); ++i) {
    if (!held[i]) out(k++) = v(i);
  }
  return out;
}

Eigen::MatrixXd restrict(const Eigen::MatrixXd& K, const std::vector<bool>& held) {
  const Eigen::Index n = std::count(held.begin(), held.end(), false);
  Eigen::MatrixXd out(n, n);
  for (Eigen::Index i = 0, a = 0; i < K.rows(); ++i) {
    if (held[i]) continue;
    for (Eigen::Index j = 0, b = 0; j < K.cols(); ++j) {
      if (!held[j]) out(a, b++) = K(i, j);
    }
    ++a;
  }
  return out;
}

Eigen::VectorXd expand(const Eigen::VectorXd& v, const std::vector<bool>& held) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(held.size()));
  for (Eigen::Index j = 0, k = 0; j < out.size(); ++j) {
    if (!held[j]) out(j) = v(k++);
  }
  return out;
}

struct Step {
  Eigen::VectorXd s;
  double predicted = 0;  // energy decrease the quadratic model predicts
  bool on_boundary = false;
};

// min -Q's + 1/2 s' K s subject to sqrt(s' M s) <= radius, solved exactly in
// the eigenbasis of the symmetric part of K with respect to M (the problems
// have tens of coordinates). Inside the region and with a convex model this
// is the Newton step with the full tangent.
Step trust_region_step(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::VectorXd& Q, double radius) {
  const Eigen::MatrixXd Ks = 0.5 * (K + K.transpose());
  auto predicted = [&](const Eigen::VectorXd& s) { return Q.dot(s) - 0.5 * s.dot(Ks * s); };
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, M);
  if (es.info() != Eigen::Success) throw std::runtime_error("static equilibrium: tangent eigenproblem failed");
  const Eigen::VectorXd& lam = es.eigenvalues();
  const Eigen::MatrixXd& V = es.eigenvectors();  // V' M V = I, so |s|_M = |t| for s = V t
  const double lam_scale = lam.cwiseAbs().maxCoeff();
  const double tiny = 1e-14 * lam_scale;
  if (lam(0) > 1e-12 * lam_scale) {
    const Eigen::VectorXd s = K.fullPivLu().solve(Q);
    if (std::sqrt(s.dot(M * s)) <= radius) return {s, predicted(s), false};
  }
  // A gradient component at the rounding level of Q is zero: a direction
  // with neither stiffness nor load (a symmetric rig's sway at the unloaded
  // nominal pose) is not to be stepped along at random.
  Eigen::VectorXd g = V.transpose() * Q;
  const double g_floor = 1e-12 * g.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < g.size(); ++i) {
    if (std::abs(g(i)) <= g_floor) g(i) = 0.0;
  }
  const double mu_lo = std::max(0.0, -lam(0));
  auto step_at = [&](double mu) {
    Eigen::VectorXd t(g.size());
    for (Eigen::Index i = 0; i < g.size(); ++i) t(i) = lam(i) + mu > 0 ? g(i) / (lam(i) + mu) : 0.0;
    return t;
  };
  Eigen::VectorXd t = step_at(mu_lo + tiny);
  if (t.norm() <= radius) {
    // The step fits with the least admissible shift: along negative
    // curvature (a saddle) continue to the boundary.
    const bool saddle = lam(0) < -1e-12 * lam_scale;
    if (saddle) t(0) += std::sqrt(std::max(0.0, radius * radius - t.squaredNorm()));
    const Eigen::VectorXd s = V * t;
    return {s, predicted(s), saddle};
  }
  // |t(mu)| falls monotonically; |t(mu_lo + |g| / radius)| <= radius.
  double lo = tiny, hi = g.norm() / radius + tiny;
  for (int it = 0; it < 200 && hi > lo * (1.0 + 1e-10); ++it) {
    const double mid = std::sqrt(lo * hi);
    (step_at(mu_lo + mid).norm() > radius ? lo : hi) = mid;
  }
  const Eigen::VectorXd s = V * step_at(mu_lo + hi);
  return {s, predicted(s), true};
}

// Very stiff rods: a rod force k (|B - A| - L) carries a rounding error of
// ~ k eps |B| that no step can remove; a search that stalls below a few
// times that has found the equilibrium as well as doubles can tell.
double rounding_floor(const RigSystem& rig) {
  const auto& g = rig.assembly().geometry;
  double reach = 0;
  for (const auto& r : g.rods) reach = std::max(reach, r.lower.norm() + r.length);
  return 16.0 * std::numeric_limits<double>::epsilon() * rig.rod_stiffness().maxCoeff() *
         (g.reference_point.norm() + reach) / rig.suspended_weight();
}

}  // namespace

// Error budget of the central differences, h the joint displacement of a
// step and l the rod length: truncation ~ (h / l)^2 k l / W relative to the
// pendulum stiffness W / l, which with rigid rods (k l / W ~ 5e5) and
// h / l = 1e-6 is 5e-7; rounding ~ eps l / h = 2e-10. The frames' parts are
// linear and differenced exactly.
Eigen::VectorXd coordinate_steps(const RigSystem& rig) {
  const double h = 1e-6 * mean_rod_length(rig);
  Eigen::VectorXd steps = Eigen::VectorXd::Constant(rig.coordinate_count(), h);
  steps.segment<3>(3).setConstant(1e-6);
  const Eigen::VectorXd reach = modal_reach(rig);
  for (int j = 0; j < rig.elastic_modes(); ++j) steps(6 + j) = reach(j) > 0 ? h / reach(j) : h;
  return steps;
}

double equilibrium_residual(const RigSystem& rig, const Eigen::VectorXd& Q) {
  // Q_j h_j / h_ref is the force at the point the coordinate moves.
  const Eigen::VectorXd steps = coordinate_steps(rig);
  const double href = steps(0);
  return (Q.cwiseProduct(steps) / href).cwiseAbs().maxCoeff() / rig.suspended_weight();
}

Eigen::MatrixXd tangent_stiffness(const RigSystem& rig, const Configuration& c) {
  const int n = rig.coordinate_count();
  const Eigen::VectorXd steps = coordinate_steps(rig);
  const Velocity rest = rig.at_rest();
  Eigen::MatrixXd K(n, n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
    s(j) = steps(j);
    const Eigen::VectorXd Qp = rig.generalized_forces(rig.displaced(c, s), rest, 0.0);
    const Eigen::VectorXd Qm = rig.generalized_forces(rig.displaced(c, -s), rest, 0.0);
    K.col(j) = -(Qp - Qm) / (2.0 * steps(j));
  }
  return K;
}

Equilibrium static_equilibrium(const RigSystem& rig, const EquilibriumOptions& options) {
  return static_equilibrium(rig, rig.nominal(), options);
}

// Why a trust region on the energy, not Newton on the forces: rods (rigid
// ones are 300 Hz springs) are five orders stiffer than the pendulum, so a
// straight step of a few millimetres across the curved valley of constant
// rod lengths stretches them to second order and raises the forces a
// thousandfold, while the energy, whose valley it is, stays a usable merit
// function. A rejected step gets one second-order correction (a step from
// the trial point with its own tangent, which pulls the rods back to length)
// before the region shrinks; the region is measured in metres of
// mass-weighted motion, sqrt(s' M s / m). Near convergence the energy
// decrease drops below the rounding of the energy and the force residual
// decides instead. The static loads are conservative (effects add only
// velocity-dependent loads at rest), so equilibrium is the energy minimum.
Equilibrium static_equilibrium(const RigSystem& rig, const Configuration& start, const EquilibriumOptions& options) {
  const int n = rig.coordinate_count();
  std::vector<bool> held(n, false);
  for (int j : options.held) {
    if (j < 0 || j >= n) throw std::invalid_argument("static_equilibrium: held coordinate out of range");
    held[j] = true;
  }
  const Velocity rest = rig.at_rest();
  struct Point {
    Configuration c;
    Eigen::VectorXd Q;
    double residual = 0, energy = 0;
  };
  auto evaluate = [&](const Configuration& c) {
    Point p{c, rig.generalized_forces(c, rest, 0.0), 0.0, rig.potential_energy(c)};
    for (int j = 0; j < n; ++j) {
      if (held[j]) p.Q(j) = 0.0;
    }
    p.residual = equilibrium_residual(rig, p.Q);
    return p;
  };
  const Eigen::MatrixXd M = restrict(rig.mass_matrix(), held) / rig.suspended_mass();
  const double L = mean_rod_length(rig);
  const double work_scale = rig.suspended_weight() * L;
  auto step_from = [&](const Point& p, double radius) {
    return trust_region_step(restrict(tangent_stiffness(rig, p.c), held), M, remove_held(p.Q, held), radius);
  };

  Point x = evaluate(start);
  double radius = 0.1 * L;
  double rho = 0;
  // rho: energy decrease over the predicted one; NaN when the prediction is
  // below the energy's rounding and the residual decides.
  auto judge = [&](const Point& from, const Point& to, double predicted) {
    const double noise = 1e3 * std::numeric_limits<double>::epsilon() * (std::abs(from.energy) + work_scale);
    if (predicted > noise) {
      rho = (from.energy - to.energy) / predicted;
      return rho > 0.1;
    }
    rho = std::numeric_limits<double>::quiet_NaN();
    return to.residual < from.residual;
  };
  Equilibrium eq;
  std::string stalled;
  for (eq.iterations = 0; eq.iterations < options.max_iterations && x.residual > options.tolerance; ++eq.iterations) {
    const Step st = step_from(x, radius);
    Point trial = evaluate(rig.displaced(x.c, expand(st.s, held)));
    bool accepted = judge(x, trial, st.predicted);
    if (!accepted) {
      const Step soc = step_from(trial, radius);
      const Point corrected = evaluate(rig.displaced(trial.c, expand(soc.s, held)));
      if (judge(x, corrected, st.predicted)) trial = corrected, accepted = true;
    }
    const double length = std::sqrt(st.s.dot(M * st.s));
    if (!accepted) {
      radius = 0.25 * length;
    } else if (rho > 0.75 && st.on_boundary) {
      radius = std::min(2.0 * radius, L);
    }
    if (accepted) x = trial;
    if (radius < 1e-13 * L) {
      stalled = "the trust region collapsed";
      break;
    }
  }
  eq.configuration = x.c;
  eq.residual = x.residual;
  eq.converged = x.residual <= options.tolerance;
  if (!eq.converged && !stalled.empty()) eq.converged = x.residual <= rounding_floor(rig);
  const std::string after = " after " + std::to_string(eq.iterations) + " steps";
  eq.message = eq.converged ? "static equilibrium found in " + std::to_string(eq.iterations) + " steps"
                            : "no static equilibrium found: residual " + std::to_string(x.residual) +
                                  " of the weight" + after + (stalled.empty() ? "" : " (" + stalled + ")");
  return eq;
}

}  // namespace rigflex::rig
