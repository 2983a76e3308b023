#include "rig/linearization.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
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

}  // namespace

const char* to_string(RigModeKind k) {
  switch (k) {
    case RigModeKind::swing: return "swing";
    case RigModeKind::deformation: return "deformation";
    case RigModeKind::rod_constraint: return "rod constraint";
  }
  return "?";
}

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
  // At the nominal pose the rods carry no load, so nothing resists sway and
  // yaw and Newton steps along them are blind. Load the rods first with the
  // swing coordinates (x, y, yaw of frame c) held, then release them: from a
  // loaded start the geometric stiffness is there and Newton converges fast
  // when the equilibrium is near the nominal pose (known limit: see docs/rig.md).
  EquilibriumOptions loading = options;
  loading.held = {0, 1, 5};
  loading.tolerance = std::max(options.tolerance, 1e-8);
  const Equilibrium loaded = static_equilibrium(rig, rig.nominal(), loading);
  Equilibrium eq = static_equilibrium(rig, loaded.converged ? loaded.configuration : rig.nominal(), options);
  eq.iterations += loaded.iterations;
  return eq;
}

Equilibrium static_equilibrium(const RigSystem& rig, const Configuration& start, const EquilibriumOptions& options) {
  const int n = rig.coordinate_count();
  std::vector<bool> held(n, false);
  for (int j : options.held) {
    if (j < 0 || j >= n) throw std::invalid_argument("static_equilibrium: held coordinate out of range");
    held[j] = true;
  }
  const Velocity rest = rig.at_rest();
  Equilibrium eq;
  eq.configuration = start;
  auto residual_of = [&](const Configuration& c) {
    Eigen::VectorXd Q = rig.generalized_forces(c, rest, 0.0);
    for (int j = 0; j < n; ++j) {
      if (held[j]) Q(j) = 0.0;
    }
    return std::pair{Q, equilibrium_residual(rig, Q)};
  };
  auto [Q, res] = residual_of(eq.configuration);
  const Eigen::MatrixXd M = rig.mass_matrix();
  // Pseudo-transient continuation: K + mu M with mu shrinking with the
  // residual. At the nominal pose the rods carry no load yet, so nothing
  // resists sway or yaw (K singular); mu M makes the first steps those of a
  // heavily damped release, and the last ones plain Newton steps.
  for (eq.iterations = 0; eq.iterations < options.max_iterations && res > options.tolerance; ++eq.iterations) {
    const double mu = std::pow(2.0 * std::numbers::pi * 0.05, 2) * std::min(1.0, res);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(restrict(tangent_stiffness(rig, eq.configuration) + mu * M, held));
    const Eigen::VectorXd s = expand(lu.solve(remove_held(Q, held)), held);
    // Backtrack while the step makes things worse. Each trial first gets two
    // corrections with the same factorization: a step along the swing
    // directions stretches the (stiff or rigid) rods to second order, a large
    // residual in the stiff directions that the tangent removes at once.
    auto corrected = [&](double lambda) {
      Configuration c = rig.displaced(eq.configuration, lambda * s);
      auto qr = residual_of(c);
      for (int k = 0; k < 2 && !(qr.second < res); ++k) {
        c = rig.displaced(c, expand(lu.solve(remove_held(qr.first, held)), held));
        qr = residual_of(c);
      }
      return std::pair{c, qr};
    };
    double lambda = 1.0;
    auto [trial, qt] = corrected(lambda);
    while (!(qt.second < res) && lambda > 1e-4) {
      lambda *= 0.5;
      std::tie(trial, qt) = corrected(lambda);
    }
    const Eigen::VectorXd& Qt = qt.first;
    const double rt = qt.second;
    if (!(rt < res)) break;  // stalled: rounding floor or no equilibrium
    eq.configuration = trial;
    Q = Qt;
    res = rt;
  }
  eq.residual = res;
  eq.converged = res <= options.tolerance;
  eq.message = eq.converged ? "static equilibrium found in " + std::to_string(eq.iterations) + " Newton steps"
                            : "no static equilibrium found: residual " + std::to_string(res) +
                                  " of the weight after " + std::to_string(eq.iterations) + " Newton steps";
  return eq;
}

Linearization linearize(const RigSystem& rig) {
  Linearization lin;
  lin.equilibrium = static_equilibrium(rig);
  if (!lin.equilibrium.converged) throw std::runtime_error(lin.equilibrium.message);
  const Eigen::MatrixXd K = tangent_stiffness(rig, lin.equilibrium.configuration);
  lin.asymmetry = (K - K.transpose()).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
  lin.K = 0.5 * (K + K.transpose());
  lin.M = rig.mass_matrix();
  const int n = rig.coordinate_count();
  // A shift below the lowest swing frequency of any real rig (0.01 Hz) keeps
  // K - sigma M positive definite.
  const double shift = -std::pow(2.0 * std::numbers::pi * 0.01, 2);
  lin.eigen = reduction::solve_dense(lin.K, lin.M, n, shift);
  reduction::check_eigenpairs(lin.K.sparseView(), lin.M.sparseView(), lin.eigen);
  const Eigen::VectorXd f = lin.eigen.frequencies_hz();
  for (Eigen::Index j = 0; j < lin.eigen.eigenvalues.size(); ++j) {
    RigMode m;
    m.frequency_hz = f(j);
    m.shape = lin.eigen.vectors.col(j);
    m.strain = rig.incremental_strain_energy(lin.equilibrium.configuration, m.shape);
    const double potential = 0.5 * std::max(lin.eigen.eigenvalues(j), 0.0);
    m.elastic_fraction = potential > 0 ? m.strain.total() / potential : 0.0;
    if (m.elastic_fraction < 0.5) {
      m.kind = RigModeKind::swing;
    } else if (rig.rods_rigid() && m.strain.rods > 0.5 * m.strain.total()) {
      m.kind = RigModeKind::rod_constraint;
    } else {
      m.kind = RigModeKind::deformation;
    }
    lin.modes.push_back(m);
  }
  return lin;
}

}  // namespace rigflex::rig
