#pragma once
// Static equilibrium of the rig (frame deflections included): the minimum of
// the potential energy (gravity, rods, frames) over the coordinates
// s = (dr, dtheta, d eta, d xf) of RigSystem::displaced, found by a
// trust-region Newton method on the exact generalized forces.
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "rig/rig_system.hpp"

namespace rigflex::rig {

struct EquilibriumOptions {
  // Converged when every generalized force, expressed as a force at its point
  // of action, is below tolerance * the suspended weight.
  double tolerance = 1e-10;
  int max_iterations = 200;
  std::vector<int> held;  // coordinates of s held at their start values
};

// Thrown by the functions that need an equilibrium and found none.
class NoEquilibrium : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Equilibrium {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  // as in EquilibriumOptions::tolerance
  Configuration configuration;
  std::string message;
};

// Finite-difference step of each coordinate of s: a displacement of 1e-6 of
// the mean rod length at the joints (see equilibrium.cpp for the error
// budget).
Eigen::VectorXd coordinate_steps(const RigSystem& rig);

// Scaled residual (see EquilibriumOptions) of the generalized forces Q at rest.
double equilibrium_residual(const RigSystem& rig, const Eigen::VectorXd& Q);

// -dQ/ds at c, at rest (not symmetrized).
Eigen::MatrixXd tangent_stiffness(const RigSystem& rig, const Configuration& c);

// From `start` (default: the nominal pose). Not converged (with the reason in
// `message`) when the trust region collapses or the iterations run out.
Equilibrium static_equilibrium(const RigSystem& rig, const Configuration& start,
                               const EquilibriumOptions& options = {});
Equilibrium static_equilibrium(const RigSystem& rig, const EquilibriumOptions& options = {});

}  // namespace rigflex::rig
