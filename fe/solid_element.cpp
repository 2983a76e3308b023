// Solid elements: isoparametric shape functions, Gauss rules on the cube and
// the tetrahedron, and the incompatible-mode condensation of the hex8.
#include "fe/solid_element.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "fe/gauss_legendre.hpp"

namespace rigflex::fe {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using NaturalDerivatives = Eigen::Matrix<double, Eigen::Dynamic, 3>;

struct Point {
  Vector3d r;
  double w;
};

// Not `Shape`: the shells' helpers (fe/shell_common.hpp) have one, and a
// unity-build source may hold both.
struct SolidShape {
  VectorXd N;
  NaturalDerivatives dN;  // dN(a, k) = dN_a / dr_k
};

// n x n x n Gauss points on [-1, 1]^3.
std::vector<Point> cube_rule(int n) {
  const auto [x, w] = gauss_legendre(n);
  std::vector<Point> rule;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) rule.push_back({Vector3d(x[i], x[j], x[k]), w[i] * w[j] * w[k]});
  return rule;
}

// Gauss points on the unit tetrahedron through the collapsed cube (Duffy):
// r = u, s = v (1 - u), t = w (1 - u)(1 - v), dV = (1 - u)^2 (1 - v) du dv dw.
// n points per direction integrate every polynomial of degree 2n - 3 exactly.
std::vector<Point> tet_rule(int n) {
  const auto [x, w] = gauss_legendre(n);
  std::vector<Point> rule;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double u = 0.5 * (1 + x[i]), v = 0.5 * (1 + x[j]), s = 0.5 * (1 + x[k]);
        const double weight = 0.125 * w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v);
        rule.push_back({Vector3d(u, v * (1 - u), s * (1 - u) * (1 - v)), weight});
      }
  return rule;
}

constexpr std::array<std::array<int, 3>, 8> kHexCorners{
    {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}};

Vector3d hex_node(int a) {
  if (a < 8) return Vector3d(kHexCorners[a][0], kHexCorners[a][1], kHexCorners[a][2]);
  const auto& e = kHexMidEdges[a - 8];
  return 0.5 * (hex_node(e[0]) + hex_node(e[1]));
}

SolidShape hex8_shape(const Vector3d& r) {
  SolidShape s{VectorXd(8), NaturalDerivatives(8, 3)};
  for (int a = 0; a < 8; ++a) {
    const Vector3d c = hex_node(a);
    const Vector3d f = (Vector3d::Ones() + c.cwiseProduct(r)) / 2;
    s.N(a) = f.prod();
    for (int k = 0; k < 3; ++k) s.dN(a, k) = 0.5 * c(k) * f((k + 1) % 3) * f((k + 2) % 3);
  }
  return s;
}

SolidShape hex20_shape(const Vector3d& r) {
  SolidShape s{VectorXd(20), NaturalDerivatives(20, 3)};
  for (int a = 0; a < 20; ++a) {
    const Vector3d c = hex_node(a);
    if (a < 8) {
      const Vector3d f = Vector3d::Ones() + c.cwiseProduct(r);
      const double sum = c.dot(r) - 2;
      s.N(a) = f.prod() * sum / 8;
      for (int k = 0; k < 3; ++k) s.dN(a, k) = c(k) * f((k + 1) % 3) * f((k + 2) % 3) * (sum + f(k)) / 8;
      continue;
    }
    // Mid-edge node: quadratic along its edge's direction k, linear across.
    int k = 0;
    while (c(k) != 0) ++k;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double q = 1 - r(k) * r(k), fi = 1 + c(i) * r(i), fj = 1 + c(j) * r(j);
    s.N(a) = q * fi * fj / 4;
    s.dN(a, k) = -2 * r(k) * fi * fj / 4;
    s.dN(a, i) = q * c(i) * fj / 4;
    s.dN(a, j) = q * fi * c(j) / 4;
  }
  return s;
}

SolidShape tet10_shape(const Vector3d& r) {
  const std::array<double, 4> L{1 - r.sum(), r(0), r(1), r(2)};
  std::array<Vector3d, 4> dL{Vector3d(-1, -1, -1), Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  SolidShape s{VectorXd(10), NaturalDerivatives(10, 3)};
  for (int a = 0; a < 4; ++a) {
    s.N(a) = L[a] * (2 * L[a] - 1);
    s.dN.row(a) = (4 * L[a] - 1) * dL[a].transpose();
  }
  for (int e = 0; e < 6; ++e) {
    const int i = kTetMidEdges[e][0], j = kTetMidEdges[e][1];
    s.N(4 + e) = 4 * L[i] * L[j];
    s.dN.row(4 + e) = 4 * (L[j] * dL[i] + L[i] * dL[j]).transpose();
  }
  return s;
}

Matrix6d elasticity(double E, double nu) {
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Matrix6d D = Matrix6d::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  D.diagonal() << lambda + 2 * mu, lambda + 2 * mu, lambda + 2 * mu, mu, mu, mu;
  return D;
}

// Strains [exx eyy ezz gxy gyz gzx] from nodal translations, given the shape
// functions' Cartesian derivatives (one row per node).
MatrixXd strain_B(const NaturalDerivatives& dNx) {
  const Eigen::Index n = dNx.rows();
  MatrixXd B = MatrixXd::Zero(6, 3 * n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const double dx = dNx(a, 0), dy = dNx(a, 1), dz = dNx(a, 2);
    B(0, 3 * a) = dx, B(3, 3 * a) = dy, B(5, 3 * a) = dz;
    B(1, 3 * a + 1) = dy, B(3, 3 * a + 1) = dx, B(4, 3 * a + 1) = dz;
    B(2, 3 * a + 2) = dz, B(4, 3 * a + 2) = dy, B(5, 3 * a + 2) = dx;
  }
  return B;
}

MatrixXd coordinates(const std::vector<Vec3>& x) {
  MatrixXd X(static_cast<Eigen::Index>(x.size()), 3);
  for (size_t a = 0; a < x.size(); ++a) X.row(static_cast<Eigen::Index>(a)) = x[a].transpose();
  return X;
}

// J(i, k) = dx_i / dr_k.
Matrix3d jacobian(const SolidShape& s, const MatrixXd& X) { return X.transpose() * s.dN; }

struct Family {
  int nodes;
  SolidShape (*shape)(const Vector3d&);
  std::vector<Point> stiffness_rule, mass_rule;
};

const Family& hex8_family() {
  // Mass with 3 points: N_a N_b det J is of degree 4 per direction on a
  // general hexahedron; 2 points are exact only on parallelepipeds.
  static const Family f{8, hex8_shape, cube_rule(2), cube_rule(3)};
  return f;
}
const Family& hex20_family() {
  static const Family f{20, hex20_shape, cube_rule(3), cube_rule(4)};
  return f;
}
const Family& tet10_family() {
  // Straight edges: B is linear (B' D B of degree 2, 3 points per direction)
  // and N_a N_b of degree 4 (4 points).
  static const Family f{10, tet10_shape, tet_rule(3), tet_rule(4)};
  return f;
}

void require_nodes(const std::vector<Vec3>& x, int n, const char* name) {
  if (static_cast<int>(x.size()) != n)
    throw std::invalid_argument(std::string(name) + ": expected " + std::to_string(n) + " nodes, got " +
                                std::to_string(x.size()));
}

MatrixXd expand_to_translations(const MatrixXd& m) {
  const Eigen::Index n = m.rows();
  MatrixXd M = MatrixXd::Zero(3 * n, 3 * n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      for (int d = 0; d < 3; ++d) M(3 * a + d, 3 * b + d) = m(a, b);
  return M;
}

// Consistent: rho integral of N_a N_b. Lumped: the diagonal of the consistent
// matrix scaled to the element's mass (Hinton-Rock-Zienkiewicz), which keeps
// every nodal mass positive where row sums would make corner masses of
// quadratic elements negative.
MatrixXd solid_mass(const Family& f, const MatrixXd& X, const SolidProperties& p) {
  const Eigen::Index n = f.nodes;
  if (p.mass == MassKind::None) return MatrixXd::Zero(3 * n, 3 * n);
  MatrixXd m = MatrixXd::Zero(n, n);
  double volume = 0;
  for (const Point& g : f.mass_rule) {
    const SolidShape s = f.shape(g.r);
    const double dv = g.w * jacobian(s, X).determinant();
    m += dv * s.N * s.N.transpose();
    volume += dv;
  }
  m *= p.rho;
  if (p.mass == MassKind::Lumped) {
    const VectorXd d = m.diagonal();
    m = (d * (p.rho * volume / d.sum())).asDiagonal();
  }
  return expand_to_translations(m);
}

MatrixXd standard_stiffness(const Family& f, const MatrixXd& X, const SolidProperties& p) {
  const Matrix6d D = elasticity(p.E, p.nu);
  MatrixXd K = MatrixXd::Zero(3 * f.nodes, 3 * f.nodes);
  for (const Point& g : f.stiffness_rule) {
    const SolidShape s = f.shape(g.r);
    const Matrix3d J = jacobian(s, X);
    const MatrixXd B = strain_B(s.dN * J.inverse());
    K += g.w * J.determinant() * B.transpose() * D * B;
  }
  return K;
}

ElementMatrices standard_element(const Family& f, const std::vector<Vec3>& x, const SolidProperties& p) {
  const MatrixXd X = coordinates(x);
  return {standard_stiffness(f, X, p), solid_mass(f, X, p)};
}

}  // namespace

ElementMatrices solid_hex8(const std::vector<Vec3>& x, const SolidProperties& p) {
  require_nodes(x, 8, "solid_hex8");
  const Family& f = hex8_family();
  const MatrixXd X = coordinates(x);
  const Matrix6d D = elasticity(p.E, p.nu);
  const Matrix3d J0 = jacobian(hex8_shape(Vector3d::Zero()), X);
  const Matrix3d J0inv = J0.inverse();
  const double det0 = J0.determinant();
  MatrixXd Kcc = MatrixXd::Zero(24, 24), Kci = MatrixXd::Zero(24, 9), Kii = MatrixXd::Zero(9, 9);
  for (const Point& g : f.stiffness_rule) {
    const SolidShape s = hex8_shape(g.r);
    const Matrix3d J = jacobian(s, X);
    const double det = J.determinant();
    const MatrixXd Bc = strain_B(s.dN * J.inverse());
    // Bubbles 1 - r_k^2, their derivatives mapped with the centre Jacobian
    // and scaled by det J0 / det J (Taylor): their strains then integrate to
    // zero over any element, which is what the patch test needs.
    const NaturalDerivatives dP = (-2 * g.r).asDiagonal().toDenseMatrix();
    const MatrixXd Bi = strain_B(dP * J0inv * (det0 / det));
    const double dv = g.w * det;
    Kcc += dv * Bc.transpose() * D * Bc;
    Kci += dv * Bc.transpose() * D * Bi;
    Kii += dv * Bi.transpose() * D * Bi;
  }
  const Eigen::LDLT<MatrixXd> internal(Kii);
  MatrixXd K = Kcc - Kci * internal.solve(Kci.transpose());
  K = 0.5 * (K + K.transpose());
  return {K, solid_mass(f, X, p)};
}

ElementMatrices solid_hex20(const std::vector<Vec3>& x, const SolidProperties& p) {
  require_nodes(x, 20, "solid_hex20");
  return standard_element(hex20_family(), x, p);
}

ElementMatrices solid_tet10(const std::vector<Vec3>& x, const SolidProperties& p) {
  require_nodes(x, 10, "solid_tet10");
  return standard_element(tet10_family(), x, p);
}

double solid_jacobian_ratio(const std::vector<Vec3>& x) {
  const Family* f = x.size() == 8    ? &hex8_family()
                    : x.size() == 20 ? &hex20_family()
                    : x.size() == 10 ? &tet10_family()
                                     : nullptr;
  if (!f) throw std::invalid_argument("solid_jacobian_ratio: a solid has 8, 20 or 10 nodes");
  const MatrixXd X = coordinates(x);
  std::vector<Vector3d> points;
  for (const Point& g : f->stiffness_rule) points.push_back(g.r);
  for (int a = 0; a < f->nodes; ++a) {
    if (f->nodes == 10) {
      static const std::array<Vector3d, 4> corners{Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                                   Vector3d::UnitZ()};
      points.push_back(a < 4 ? corners[a]
                             : Vector3d(0.5 * (corners[kTetMidEdges[a - 4][0]] + corners[kTetMidEdges[a - 4][1]])));
    } else {
      points.push_back(hex_node(a));
    }
  }
  double lo = INFINITY, sum = 0;
  for (const Vector3d& r : points) {
    const double d = jacobian(f->shape(r), X).determinant();
    lo = std::min(lo, d);
    sum += d;
  }
  const double mean = sum / static_cast<double>(points.size());
  if (!(std::abs(mean) > 0) || !std::isfinite(mean)) return lo > 0 ? 0.0 : -1.0;
  return lo / std::abs(mean);
}

}  // namespace rigflex::fe
