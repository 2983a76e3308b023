#include "fe/shell_common.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "fe/gauss_legendre.hpp"

namespace rigflex::fe::shell_detail {

double LocalFrame::length() const { return std::sqrt(area); }

double LocalFrame::max_warp() const { return z.cwiseAbs().maxCoeff() / length(); }

LocalFrame make_local_frame(const std::vector<Vec3>& x) {
  if (x.size() != 4 && x.size() != 8)
    throw std::invalid_argument("shell element: expected 4 or 8 nodes, got " + std::to_string(x.size()));
  for (const Vec3& p : x)
    if (!p.allFinite()) throw std::invalid_argument("shell element: non-finite node coordinate");

  LocalFrame f;
  f.origin = (x[0] + x[1] + x[2] + x[3]) / 4.0;
  const Vec3 normal = (x[2] - x[0]).cross(x[3] - x[1]);
  f.area = 0.5 * normal.norm();
  if (!(f.area > 0.0)) throw std::invalid_argument("shell element: zero area");
  const Vec3 e3 = normal.normalized();
  Vec3 d = 0.5 * ((x[1] + x[2]) - (x[3] + x[0]));
  d -= d.dot(e3) * e3;
  // A non-degenerate quadrilateral has a non-zero "width" along its mean
  // ξ direction; fall back to edge 1-2 only for pathological input.
  if (d.norm() <= 1e-12 * f.length()) d = (x[1] - x[0]) - (x[1] - x[0]).dot(e3) * e3;
  const Vec3 e1 = d.normalized();
  f.R.row(0) = e1.transpose();
  f.R.row(1) = e3.cross(e1).transpose();
  f.R.row(2) = e3.transpose();

  const auto n = static_cast<Eigen::Index>(x.size());
  f.xy.resize(n, 2);
  f.z.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 local = f.R * (x[static_cast<size_t>(i)] - f.origin);
    f.xy.row(i) = local.head<2>().transpose();
    f.z(i) = local.z();
  }
  return f;
}

std::vector<GaussPoint> gauss_rule(int n) {
  const GaussLegendre g = gauss_legendre(n);
  std::vector<GaussPoint> rule;
  for (size_t j = 0; j < g.x.size(); ++j)
    for (size_t i = 0; i < g.x.size(); ++i) rule.push_back({g.x[i], g.x[j], g.w[i] * g.w[j]});
  return rule;
}

Vector2d node_reference_coords(int node) {
  static const double c[9][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}};
  return {c[node][0], c[node][1]};
}

Shape shape_q4(double xi, double eta) {
  Shape s;
  s.N.resize(4);
  s.dN.resize(4, 2);
  for (int i = 0; i < 4; ++i) {
    const Vector2d r = node_reference_coords(i);
    s.N(i) = 0.25 * (1 + r.x() * xi) * (1 + r.y() * eta);
    s.dN(i, 0) = 0.25 * r.x() * (1 + r.y() * eta);
    s.dN(i, 1) = 0.25 * r.y() * (1 + r.x() * xi);
  }
  return s;
}

Shape shape_q8(double xi, double eta) {
  Shape s;
  s.N.resize(8);
  s.dN.resize(8, 2);
  for (int i = 0; i < 4; ++i) {
    const double a = node_reference_coords(i).x(), b = node_reference_coords(i).y();
    s.N(i) = 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1);
    s.dN(i, 0) = 0.25 * a * (1 + b * eta) * (2 * a * xi + b * eta);
    s.dN(i, 1) = 0.25 * b * (1 + a * xi) * (a * xi + 2 * b * eta);
  }
  for (int i = 4; i < 8; ++i) {
    const double a = node_reference_coords(i).x(), b = node_reference_coords(i).y();
    if (a == 0.0) {  // mid-side of an edge eta = b
      s.N(i) = 0.5 * (1 - xi * xi) * (1 + b * eta);
      s.dN(i, 0) = -xi * (1 + b * eta);
      s.dN(i, 1) = 0.5 * b * (1 - xi * xi);
    } else {  // mid-side of an edge xi = a
      s.N(i) = 0.5 * (1 + a * xi) * (1 - eta * eta);
      s.dN(i, 0) = 0.5 * a * (1 - eta * eta);
      s.dN(i, 1) = -eta * (1 + a * xi);
    }
  }
  return s;
}

Matrix2d jacobian(const Shape& s, const Eigen::MatrixX2d& xy) { return s.dN.transpose() * xy; }

Eigen::MatrixX2d cartesian_derivatives(const Shape& s, const Matrix2d& J) {
  // grad_ref = J grad_xy for each shape function: dN_xy^T = J^-1 dN^T.
  return (J.inverse() * s.dN.transpose()).transpose();
}

double checked_det(const Matrix2d& J) {
  const double det = J.determinant();
  if (!(det > 0.0))
    throw std::invalid_argument("shell element: non-positive Jacobian (distorted, concave or degenerate element)");
  return det;
}

Matrix3d plane_stress(double E, double nu) {
  Matrix3d C;
  C << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
  return E / (1.0 - nu * nu) * C;
}

Matrix3d membrane_rigidity(const ShellProperties& p) { return p.thickness * plane_stress(p.E, p.nu); }

Matrix3d bending_rigidity(const ShellProperties& p) {
  return std::pow(p.thickness, 3) / 12.0 * plane_stress(p.E, p.nu);
}

double shear_rigidity(const ShellProperties& p) {
  const double G = p.E / (2.0 * (1.0 + p.nu));
  return 5.0 / 6.0 * G * p.thickness;
}

void check_properties(const ShellProperties& p) {
  if (!(std::isfinite(p.E) && p.E > 0.0)) throw std::invalid_argument("shell element: E must be positive");
  if (!(std::isfinite(p.nu) && p.nu > -1.0 && p.nu < 0.5))
    throw std::invalid_argument("shell element: nu must lie in (-1, 0.5)");
  if (!(std::isfinite(p.thickness) && p.thickness > 0.0))
    throw std::invalid_argument("shell element: thickness must be positive");
  if (!(std::isfinite(p.rho) && p.rho >= 0.0)) throw std::invalid_argument("shell element: rho must be >= 0");
}

MatrixXd membrane_B(const Eigen::MatrixX2d& dNxy) {
  const auto n = static_cast<int>(dNxy.rows());
  MatrixXd B = MatrixXd::Zero(3, 6 * n);
  for (int i = 0; i < n; ++i) {
    B(0, dof(i, kU)) = dNxy(i, 0);
    B(1, dof(i, kV)) = dNxy(i, 1);
    B(2, dof(i, kU)) = dNxy(i, 1);
    B(2, dof(i, kV)) = dNxy(i, 0);
  }
  return B;
}

MatrixXd bending_B(const Eigen::MatrixX2d& dNxy) {
  const auto n = static_cast<int>(dNxy.rows());
  MatrixXd B = MatrixXd::Zero(3, 6 * n);
  for (int i = 0; i < n; ++i) {
    B(0, dof(i, kTy)) = dNxy(i, 0);
    B(1, dof(i, kTx)) = -dNxy(i, 1);
    B(2, dof(i, kTy)) = dNxy(i, 1);
    B(2, dof(i, kTx)) = -dNxy(i, 0);
  }
  return B;
}

// Drilling stiffness. The membrane fields carry no stiffness for the
// rotation tz about the normal, which a shell meeting other shells or beams
// at an angle needs. It is the Hughes-Brezzi penalty
//   gamma G t integral (tz - omega)^2 dA,   omega = (v_x - u_y)/2,
// with tz interpolated like the displacements and integrated with the
// element's full membrane rule. Why this form:
//  - zero for every rigid motion and for every constant-strain state, so
//    the patch tests pass; zero for pure in-plane bending of a rectangle,
//    because omega includes the enhanced membrane field (MITC4 incompatible
//    modes, Quad8 quadratic terms) and is then exactly linear. A penalty on
//    the nodal tz alone (their deviation from the element mean, 1e-2 G t A)
//    stiffened the in-plane bending of a web one element deep by 4.7 %
//    (square elements) and 21 % (2:1): measured, rejected.
//  - the full rule (2x2 on 4 nodes, 3x3 on 8) sees every nodal pattern of
//    tz, so no spurious zero-energy modes remain (6 rigid modes exactly).
//  - gamma = 1e-2, not the 1 of Hughes & Brezzi: at a fold (box girder
//    corner) tz of one wall is the bending rotation of the other, i.e. the
//    rotation of the fold line, while omega of a wall in shear is half of
//    that; the penalty turns the difference into artificial stiffness that
//    grows with gamma: a square box in torsion (4 MITC4 per side,
//    test_shell_box.cpp) is 1.65 % too stiff with gamma = 1, 0.36 % with
//    0.1 and 0.06 % with 1e-2. Commercial codes use
//    1e-5 .. 1e-3 G t A for the same reason (Nastran K6ROT).
//  - the drilling rotation carries no mass (shell_mass), so the penalty
//    makes no modes of its own: against a rotary inertia rho t^3/12 it put
//    a band at sqrt(12 gamma G / rho) / (2 pi t) = 170 Hz m / t, among the
//    physical modes of plates thicker than about 0.1 m. A point mass's
//    rotary inertia about the normal still meets only this penalty.
double drilling_modulus(const ShellProperties& p) {
  constexpr double gamma = 1e-2;
  return gamma * p.E / (2.0 * (1.0 + p.nu)) * p.thickness;
}

RowVectorXd drilling_row(const Shape& s, const Eigen::MatrixX2d& dNxy) {
  const auto n = static_cast<int>(s.N.size());
  RowVectorXd r = RowVectorXd::Zero(6 * n);
  for (int i = 0; i < n; ++i) {
    r(dof(i, kTz)) = s.N(i);
    r(dof(i, kU)) = 0.5 * dNxy(i, 1);
    r(dof(i, kV)) = -0.5 * dNxy(i, 0);
  }
  return r;
}

namespace {

// N'N integrated over the projected element (n x n), scaled afterwards.
MatrixXd shape_gram(const LocalFrame& f, ShapeFn shape, int rule) {
  const auto n = f.xy.rows();
  MatrixXd G = MatrixXd::Zero(n, n);
  for (const GaussPoint& g : gauss_rule(rule)) {
    const Shape s = shape(g.xi, g.eta);
    const double w = g.weight * checked_det(jacobian(s, f.xy));
    G += w * s.N * s.N.transpose();
  }
  return G;
}

// Row-sum lumping keeps the total and, for bilinear shapes on convex
// elements, positive nodal masses. Serendipity corner row sums are negative,
// so the 8-node element scales the consistent diagonal instead (Hinton,
// Rock & Zienkiewicz), which preserves the total and keeps every mass positive.
MatrixXd lump(const MatrixXd& G) {
  if (G.rows() == 4) return G.rowwise().sum().asDiagonal();
  const VectorXd d = G.diagonal();
  return (d * (G.sum() / d.sum())).asDiagonal();
}

}  // namespace

MatrixXd shell_mass(const LocalFrame& f, ShapeFn shape, int rule, const ShellProperties& p) {
  const auto n = static_cast<int>(f.xy.rows());
  MatrixXd M = MatrixXd::Zero(6 * n, 6 * n);
  if (p.mass == MassKind::None || p.rho == 0.0) return M;
  MatrixXd G = shape_gram(f, shape, rule);
  if (p.mass == MassKind::Lumped) G = lump(G);
  const double translational = p.rho * p.thickness;
  // Rotary inertia rho t^3/12 about the two in-plane axes only: it is the
  // inertia of the normal fibre turning about them. About the normal the
  // fibre turns about its own axis and has none; the in-plane rotation of
  // the material is carried by the translations' mass already. Giving the
  // drilling rotation rho t^3/12 as well (as before) put a band of spurious
  // drilling modes at sqrt(12 gamma G / rho) / (2 pi t) = 170 Hz m / t, among
  // the physical modes of thick plates; massless, the drilling DOFs give
  // infinite eigenvalues, which the eigen solver never returns.
  const double rotary = p.rho * std::pow(p.thickness, 3) / 12.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      for (int a = 0; a < 3; ++a) M(dof(i, a), dof(j, a)) = translational * G(i, j);
      for (int a : {kTx, kTy}) M(dof(i, a), dof(j, a)) = rotary * G(i, j);
    }
  return M;
}

ElementMatrices to_global(const MatrixXd& K_local, const MatrixXd& M_local, const LocalFrame& f) {
  const auto n = static_cast<int>(f.xy.rows());
  // Rows past the nodes' are the element's own coordinates: frame-free.
  MatrixXd T = MatrixXd::Identity(K_local.rows(), K_local.rows());
  for (int i = 0; i < n; ++i) {
    // Local DOFs at the actual node -> DOFs at its projection p = x - z e3,
    // through a rigid link: u_p = u + theta x (p - x) = u - z (ty, -tx, 0).
    Eigen::Matrix<double, 6, 6> W = Eigen::Matrix<double, 6, 6>::Identity();
    W(kU, kTy) = -f.z(i);
    W(kV, kTx) = f.z(i);
    Eigen::Matrix<double, 6, 6> Rb = Eigen::Matrix<double, 6, 6>::Zero();
    Rb.topLeftCorner<3, 3>() = f.R;
    Rb.bottomRightCorner<3, 3>() = f.R;
    T.block<6, 6>(6 * i, 6 * i) = W * Rb;
  }
  ElementMatrices out;
  out.K = T.transpose() * K_local * T;
  out.M = T.transpose() * M_local * T;
  // Remove round-off asymmetry so that assembly may trust either triangle.
  out.K = 0.5 * (out.K + out.K.transpose()).eval();
  out.M = 0.5 * (out.M + out.M.transpose()).eval();
  return out;
}

}  // namespace rigflex::fe::shell_detail
