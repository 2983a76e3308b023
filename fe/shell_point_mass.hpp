#pragma once
// A point mass on a node that only flat shells carry. Its rotary inertia
// about the shells' normal has no rotation of its own to act on there: the
// node's drilling rotation is no motion of a shell (its only stiffness is
// the drilling stabilization), and an inertia on it made a spurious mode
// whose frequency fell as the mesh was refined. Its rotary inertia about
// the in-plane axes, on one node's rotations, has a (slower) mesh
// dependence of its own. So the rotary inertia acts on the rigid rotation
// of a footprint of fixed size, as a distributing coupling would carry it.
#include <Eigen/Dense>
#include <vector>

#include "fe/model.hpp"

namespace rigflex::fe {

// The DOFs (node_index * 6 + local DOF) a point mass acts on and its mass
// matrix on them.
struct PointMassMatrix {
  std::vector<long> dofs;
  Eigen::MatrixXd M;
};

// Shells at a node count as one plane when their normals lie within this
// angle of their mean; at a sharper fold one wall's drilling rotation is
// the other's bending rotation, a physical DOF.
constexpr double kShellPlaneDegrees = 5.0;

// One entry per model.point_masses, in order. A mass with rotary inertia
// whose node lies only on shells within kShellPlaneDegrees of one plane (no
// beam, solid, spring, coupling or support of a rotation there) acts with
// its mass on the node's translations and with its inertia on the
// least-squares rigid rotation of its footprint's translations (the
// rotation rows of distributing_link): the shells around the node and every
// shell in that plane reached within the mass's largest radius of gyration
// sqrt(J_max / m), sampled evenly by distance to at most 100 nodes. A mass
// of zero with an inertia has no radius of gyration: its footprint is the
// shells around its node, which shrink with the mesh. Rigid motions are
// exact, so the model's mass properties are unchanged. Every other mass
// acts on its node's six DOFs as given. The model must be valid.
std::vector<PointMassMatrix> point_mass_matrices(const Model& model);

}  // namespace rigflex::fe
