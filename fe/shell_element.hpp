#pragma once
// Flat-facet shell elements: membrane + Reissner-Mindlin bending + drilling
// stabilization, formed in a local element frame and rotated to global axes.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

struct ShellProperties {
  double E = 0.0, nu = 0.0, rho = 0.0, thickness = 0.0;
  MassKind mass = MassKind::Consistent;
};

// 4-node MITC4 (assumed transverse shear strains tied at the edge midpoints)
// with an incompatible-mode membrane. x: 4 corner positions,
// counter-clockwise about the normal (the normal follows the node order).
// A slightly warped element is projected onto its mean plane and attached
// to its nodes through rigid offsets.
ElementMatrices shell_mitc4(const std::vector<Vec3>& x, const ShellProperties& p);

// 8-node quadrilateral: corners counter-clockwise, then mid-sides 1-2, 2-3,
// 3-4, 4-1 (CalculiX S8 / Abaqus node order). Serendipity membrane; plate
// bending from the 9-node MITC9 field with the centre node condensed
// statically. Flat: all 8 nodes must lie (nearly) in one plane.
ElementMatrices shell_quad8(const std::vector<Vec3>& x, const ShellProperties& p);

// The same element with the centre kept: 51 x 51, the 8 nodes' 48 DOFs then
// the element's own three coordinates, the centre's w, tx, ty (local axes)
// above the 8 nodes' serendipity interpolation. They are zero in every rigid
// motion and carry the centre's own inertia, which the condensed element
// leaves out (thick plates converge as h^4 instead of h^2). Consistent mass
// only.
ElementMatrices shell_quad8_with_centre(const std::vector<Vec3>& x, const ShellProperties& p);

// Both throw std::invalid_argument for a wrong node count, non-physical
// properties or a non-positive Jacobian; check_shell_geometry() reports
// geometry problems to the user first.

// Checks the element geometry: a node count of fe/shell_types.hpp, no coincident nodes, warp
// (node distance from the mean plane) at most 1 % of the element size,
// positive Jacobian at the integration points and at the nodes. Throws
// ModelError({"shell", element_id, "nodes"}, ...).
void check_shell_geometry(const std::vector<Vec3>& x, const std::string& element_id);

}  // namespace rigflex::fe
