#pragma once
// Continuum (solid) elements: 8-node hexahedron with incompatible modes,
// 20-node serendipity hexahedron and 10-node tetrahedron, isotropic linear
// elastic. Their nodes carry translations only: the matrices are 3n x 3n,
// DOFs node by node [UX UY UZ] in global axes (the element loop places them
// on the first three of the node's six DOFs; rotations nothing else stiffens
// are dropped at assembly).
//
// Node orders are VTK's and CalculiX's: hexahedra corners 1-4 on one face
// counter-clockwise seen from the opposite face, 5-8 above them; hex20
// mid-edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8;
// tet10 corners 1-4 (4 on the side of 1-2-3 where (x2-x1) x (x3-x1) points),
// mid-edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
#include <array>
#include <vector>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

// The corner pairs (0-based) whose mid-edge nodes follow the corners, in
// node order: the hex20's and the tet10's, as described above.
inline constexpr std::array<std::array<int, 2>, 12> kHexMidEdges{
    {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
inline constexpr std::array<std::array<int, 2>, 6> kTetMidEdges{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};

struct SolidProperties {
  double E = 0.0;
  double nu = 0.0;
  double rho = 0.0;
  MassKind mass = MassKind::Consistent;
};

// Wilson-Taylor incompatible modes (nine internal bubble DOFs, condensed),
// derivatives taken with the centre Jacobian so that the element passes the
// patch test on any shape: a single element through a beam's depth bends
// exactly when it is a parallelepiped (no shear locking), and has no spurious
// zero-energy mode (full 2x2x2 integration).
ElementMatrices solid_hex8(const std::vector<Vec3>& x, const SolidProperties& p);
// Serendipity, full 3x3x3 integration (no hourglass modes).
ElementMatrices solid_hex20(const std::vector<Vec3>& x, const SolidProperties& p);
// Quadratic tetrahedron; the rules integrate a straight-edged element's
// stiffness and consistent mass exactly.
ElementMatrices solid_tet10(const std::vector<Vec3>& x, const SolidProperties& p);

// Smallest det(J) / (mean det(J)) over the element's integration points and
// nodes: <= 0 for an inverted or tangled element (nodes in the wrong order).
double solid_jacobian_ratio(const std::vector<Vec3>& x);

}  // namespace rigflex::fe
