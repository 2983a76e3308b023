#pragma once
// Flat-facet shell elements: membrane + Reissner-Mindlin bending + drilling
// stabilization, formed in a local element frame and rotated to global axes.
#include <Eigen/Dense>
#include <vector>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

struct ShellProperties {
  double E = 0.0, nu = 0.0, rho = 0.0, thickness = 0.0;
  MassKind mass = MassKind::Consistent;
};

// 4-node MITC4 (assumed transverse shear strains tied at the edge midpoints).
// x: 4 corner positions, counter-clockwise.
ElementMatrices shell_mitc4(const std::vector<Vec3>& x, const ShellProperties& p);

// 8-node serendipity quadrilateral: corners counter-clockwise, then mid-sides
// 1-2, 2-3, 3-4, 4-1 (CalculiX S8 / Abaqus node order).
ElementMatrices shell_quad8(const std::vector<Vec3>& x, const ShellProperties& p);

// Checks the element geometry (positive Jacobian at the integration points,
// no coincident nodes); throws ModelError naming `element_id`.
void check_shell_geometry(const std::vector<Vec3>& x, const std::string& element_id);

}  // namespace rigflex::fe
