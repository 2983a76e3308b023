#pragma once
// The linearization about the static equilibrium: K = -dQ/ds by central differences of the exact generalized forces, so
// the geometric stiffness of the rods under gravity (what makes a pendulum
// swing) comes with the material stiffness, and M the constant mass matrix of
// the coordinates s = (dr, dtheta, d eta, d xf) of RigSystem::displaced.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "linalg/eigen_solver.hpp"
#include "rig/equilibrium.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::rig {

// swing: the suspended body swinging on the rods, its potential energy
// mostly gravity's (elastic_fraction < 0.5) and most of the mode's mass in
// the body (body_fraction >= 0.5: a frame joint swinging on the tensioned
// rods is a local frame mode, not a swing). rod_constraint: the rods' axial
// stretch in a rig with rigid rods. deformation: the rest.
enum class RigModeKind { swing, deformation, rod_constraint };
const char* to_string(RigModeKind k);

struct RigMode {
  double frequency_hz = 0;
  RigModeKind kind = RigModeKind::swing;
  double elastic_fraction = 0;  // strain energy / total potential energy of the mode
  double body_fraction = 0;     // kinetic energy share of carrying frame + body (rigid motion)
  StrainEnergy strain;          // strain energy by component (J, for the M-normalized shape)
  Eigen::VectorXd shape;        // M-normalized, coordinates s
};

struct Linearization {
  Equilibrium equilibrium;
  Eigen::MatrixXd K, M;        // symmetrized K
  double asymmetry = 0;        // max |K - K'| / max |K|
  linalg::EigenResult eigen;
  std::vector<RigMode> modes;  // ascending frequency
};

// Throws NoEquilibrium when no static equilibrium is found.
Linearization linearize(const RigSystem& rig);

}  // namespace rigflex::rig
