#pragma once
// Pieces shared by the flat-facet shell elements (shell_mitc4.cpp,
// shell_quad8.cpp, shell_element.cpp): the local element frame, quadrature,
// serendipity shape functions, constitutive matrices, drilling
// stabilization, mass, and the rotation of local matrices to global axes.
// Internal to rigflex_fe; not part of the public API.
#include <Eigen/Dense>
#include <vector>

#include "fe/shell_element.hpp"

namespace rigflex::fe::shell_detail {

using Eigen::Matrix2d;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::Vector2d;
using Eigen::VectorXd;

// Position of a local DOF in the element vector (6 per node, node-major,
// local axes: u v w along e1 e2 e3, then rotation-vector components tx ty tz).
enum LocalDof : int { kU = 0, kV = 1, kW = 2, kTx = 3, kTy = 4, kTz = 5 };
inline int dof(int node, int local) { return 6 * node + local; }

// Orthonormal element frame. e3 is the normal from the cross product of the
// corner diagonals (so the corners run counter-clockwise about e3 and a
// clockwise numbering only flips the normal); e1 points from the middle of
// edge 4-1 to the middle of edge 2-3, projected into the mean plane.
struct LocalFrame {
  Matrix3d R;               // rows e1, e2, e3: local vector = R * global vector
  Vec3 origin;              // centroid of the corners
  Eigen::MatrixX2d xy;      // nodes projected onto the mean plane, local coords
  VectorXd z;               // signed distance of each node from the mean plane
  double area = 0.0;        // area of the projected corner quadrilateral
  double length() const;    // sqrt(area): the element size used for ratios
  double max_warp() const;  // max |z| / length()
};

// Throws std::invalid_argument unless x holds 4 or 8 finite points.
LocalFrame make_local_frame(const std::vector<Vec3>& x);

struct GaussPoint {
  double xi, eta, weight;
};
// n x n Gauss-Legendre rule on [-1,1]^2, n = 1, 2 or 3.
std::vector<GaussPoint> gauss_rule(int n);

// Shape functions at a point of the reference square: N (n) and their
// derivatives dN (n x 2: d/dxi, d/deta).
struct Shape {
  VectorXd N;
  Eigen::MatrixX2d dN;
};
Shape shape_q4(double xi, double eta);
// Serendipity: corners, then mid-sides 1-2, 2-3, 3-4, 4-1.
Shape shape_q8(double xi, double eta);
using ShapeFn = Shape (*)(double, double);

// Reference coordinates of the element nodes: 4 corners, 4 mid-sides, then
// the centre (node index 8, used by the 9-node bending field of Quad8).
Vector2d node_reference_coords(int node);

// J = [[x_xi, y_xi], [x_eta, y_eta]], so that grad_ref = J * grad_xy.
Matrix2d jacobian(const Shape& s, const Eigen::MatrixX2d& xy);
// Cartesian derivatives (n x 2: d/dx, d/dy) given the Jacobian.
Eigen::MatrixX2d cartesian_derivatives(const Shape& s, const Matrix2d& J);

// Isotropic plane-stress elasticity matrix [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]]
// times E/(1-nu^2); the membrane and bending rigidities scale it by t and t^3/12.
Matrix3d plane_stress(double E, double nu);
Matrix3d membrane_rigidity(const ShellProperties& p);
Matrix3d bending_rigidity(const ShellProperties& p);
// Transverse shear rigidity k G t with Reissner's k = 5/6.
double shear_rigidity(const ShellProperties& p);

// Throws std::invalid_argument for non-physical properties; the model
// validation reports them to the user first, this only guards the library.
void check_properties(const ShellProperties& p);

// Membrane strain row-matrix [u_x; v_y; u_y + v_x] (3 x 6n) from Cartesian
// shape derivatives of the compatible field.
MatrixXd membrane_B(const Eigen::MatrixX2d& dNxy);
// Curvatures [tx..]: k_xx = ty_x, k_yy = -tx_y, k_xy = ty_y - tx_x, from the
// rotation vector (the mid-surface fibre rotates by beta = (ty, -tx)).
MatrixXd bending_B(const Eigen::MatrixX2d& dNxy);

// Drilling stiffness gamma G t integral (tz - omega)^2 (see shell_common.cpp
// for the form, the factor and why): the modulus gamma G t, and the row
// tz - (v_x - u_y)/2 of the compatible field at a point.
double drilling_modulus(const ShellProperties& p);
RowVectorXd drilling_row(const Shape& s, const Eigen::MatrixX2d& dNxy);

// Local mass matrix: rho t N'N on u v w and rho t^3/12 N'N on tx ty (the
// drilling rotation tz carries none), integrated with an n x n rule; lumped
// by row sums (4 nodes) or HRZ diagonal scaling (8 nodes); zero for
// MassKind::None. The 8-node element replaces the consistent w, tx, ty
// part by its 9-node field's (shell_quad8.cpp).
MatrixXd shell_mass(const LocalFrame& f, ShapeFn shape, int rule, const ShellProperties& p);

// Rotates local matrices (formed on the projected, flat element) to global
// axes at the actual nodes, through rigid offsets along e3 for warped nodes.
// Rows past the 6 per node (an element's own coordinates) are kept as they are.
ElementMatrices to_global(const MatrixXd& K_local, const MatrixXd& M_local, const LocalFrame& f);

// Throws std::invalid_argument if the Jacobian is not positive at a point
// the element integrates over; check_shell_geometry() gives the user-facing
// message, this guards direct calls.
double checked_det(const Matrix2d& J);

}  // namespace rigflex::fe::shell_detail
