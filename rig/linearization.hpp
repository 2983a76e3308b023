#pragma once
// Static equilibrium (frame deflections included) and the linearization about
// it: K = -dQ/ds by central differences of the exact generalized forces, so
// the geometric stiffness of the rods under gravity (what makes a pendulum
// swing) comes with the material stiffness, and M the constant mass matrix of
// the coordinates s = (dr, dtheta, d eta, d xf) of RigSystem::displaced.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "reduction/eigen_solver.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::rig {

struct EquilibriumOptions {
  // Converged when every generalized force, expressed as a force at its point
  // of action, is below tolerance * the suspended weight.
  double tolerance = 1e-10;
  int max_iterations = 60;
  std::vector<int> held;  // coordinates of s held at their start values
};

struct Equilibrium {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  // as in EquilibriumOptions::tolerance
  Configuration configuration;
  std::string message;
};

// Finite-difference step of each coordinate of s: a displacement of 1e-6 of
// the mean rod length at the joints (see linearization.cpp for the error
// budget).
Eigen::VectorXd coordinate_steps(const RigSystem& rig);

// Scaled residual (see EquilibriumOptions) of the generalized forces Q at rest.
double equilibrium_residual(const RigSystem& rig, const Eigen::VectorXd& Q);

// Newton iteration from `start` (default: the nominal pose).
Equilibrium static_equilibrium(const RigSystem& rig, const Configuration& start,
                               const EquilibriumOptions& options = {});
Equilibrium static_equilibrium(const RigSystem& rig, const EquilibriumOptions& options = {});

// -dQ/ds at c, at rest (not symmetrized).
Eigen::MatrixXd tangent_stiffness(const RigSystem& rig, const Configuration& c);

enum class RigModeKind { swing, deformation, rod_constraint };
const char* to_string(RigModeKind k);

struct RigMode {
  double frequency_hz = 0;
  RigModeKind kind = RigModeKind::swing;
  double elastic_fraction = 0;  // strain energy / total potential energy of the mode
  StrainEnergy strain;          // strain energy by component (J, for the M-normalized shape)
  Eigen::VectorXd shape;        // M-normalized, coordinates s
};

struct Linearization {
  Equilibrium equilibrium;
  Eigen::MatrixXd K, M;        // symmetrized K
  double asymmetry = 0;        // max |K - K'| / max |K|
  reduction::EigenResult eigen;
  std::vector<RigMode> modes;  // ascending frequency
};

// Throws std::runtime_error when no static equilibrium is found.
Linearization linearize(const RigSystem& rig);

}  // namespace rigflex::rig
