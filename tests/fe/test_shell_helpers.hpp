#pragma once
// Helpers for the shell element tests: dense element eigen-analysis, plate
// meshes built directly as fe::Model (independent of the meshers under
// test elsewhere), and a small shift-invert subspace iteration so that the
// mesh tests do not depend on the reduction module's solver.

// GCC 12 reports false -Wmaybe-uninitialized warnings inside Eigen 3.4's
// self-adjoint products, instantiated by the eigen solvers used here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "fe/assembly.hpp"
#include "fe/model.hpp"
#include "fe/shell_centres.hpp"
#include "fe/shell_element.hpp"

namespace rigflex::fe::shell_test {

inline constexpr double kE = 200e9, kNu = 0.3, kRho = 8000.0;  // steel (Pa, -, kg/m^3)

using std::numbers::pi;

// Eigenvalues of K after symmetric diagonal (Jacobi) scaling, ascending.
// The scaling makes membrane, bending and drilling terms comparable, so a
// relative threshold separates rigid-body modes from soft physical ones.
inline Eigen::VectorXd scaled_eigenvalues(const Eigen::MatrixXd& K) {
  const Eigen::VectorXd d = K.diagonal().cwiseAbs().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd S = d.asDiagonal() * K * d.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
}

// Number of eigenvalues of the scaled K below `rel` times the largest one.
inline int count_zero_modes(const Eigen::MatrixXd& K, double rel = 1e-10) {
  const Eigen::VectorXd ev = scaled_eigenvalues(K);
  int n = 0;
  for (double v : ev)
    if (std::abs(v) < rel * ev(ev.size() - 1)) ++n;
  return n;
}

// Rigid-body motion (translation t, small rotation r about point c) as the
// 6-per-node vector of the given node positions.
inline Eigen::VectorXd rigid_motion(const std::vector<Vec3>& x, const Vec3& t, const Vec3& r, const Vec3& c) {
  Eigen::VectorXd u(6 * static_cast<Eigen::Index>(x.size()));
  for (size_t i = 0; i < x.size(); ++i) {
    u.segment<3>(6 * static_cast<Eigen::Index>(i)) = t + r.cross(x[i] - c);
    u.segment<3>(6 * static_cast<Eigen::Index>(i) + 3) = r;
  }
  return u;
}

inline ElementMatrices element(const std::vector<Vec3>& x, const ShellProperties& p) {
  return x.size() == 8 ? shell_quad8(x, p) : shell_mitc4(x, p);
}

// Adds the mid-side nodes (edge mid-points) to 4 corners.
inline std::vector<Vec3> with_midsides(const std::vector<Vec3>& c) {
  std::vector<Vec3> x = c;
  for (size_t i = 0; i < 4; ++i) x.push_back(0.5 * (c[i] + c[(i + 1) % 4]));
  return x;
}

// A general rotation, so that no element axis coincides with a global one.
inline Eigen::Matrix3d general_rotation() {
  return Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
}

struct Steel {
  double E = 200e9, nu = 0.3, rho = 8000.0;
};

// "prefix" followed by the numbers joined by '_'. Built with += because
// GCC 12 warns falsely (-Wrestrict, bug 105329) on "literal" + std::string.
inline std::string label(const char* prefix, long a, long b = -1) {
  std::string s(prefix);
  s += std::to_string(a);
  if (b >= 0) {
    s += '_';
    s += std::to_string(b);
  }
  return s;
}

// Model with one material "m" and one shell section "s".
inline Model empty_model(double E, double nu, double rho, double t) {
  Model m;
  m.materials["m"] = Material{"m", E, nu, rho};
  m.shell_sections["s"] = ShellSection{"s", "m", t};
  return m;
}

// Structured a x b plate in the XY plane (origin at a corner), nx x ny
// elements, MITC4 or Quad8. The grid's element-centre points are not
// nodes; Quad8 elements with consistent mass get their centre coordinates'
// node (add_shell_centres), as models read from files do.
struct PlateMesh {
  Model model;
  int nx = 0, ny = 0;
  bool quadratic = false;
};

inline PlateMesh plate_mesh(double a, double b, int nx, int ny, bool quadratic, double E, double nu, double rho,
                            double t, MassKind mass = MassKind::Consistent) {
  PlateMesh pm{empty_model(E, nu, rho, t), nx, ny, quadratic};
  const int s = quadratic ? 2 : 1;  // grid steps per element
  const int gx = s * nx, gy = s * ny;
  auto id = [&](int i, int j) { return NodeId{1 + i + j * (gx + 1)}; };
  for (int j = 0; j <= gy; ++j)
    for (int i = 0; i <= gx; ++i) {
      if (quadratic && i % 2 == 1 && j % 2 == 1) continue;
      pm.model.add_node(id(i, j), Vec3(a * i / gx, b * j / gy, 0.0));
    }
  for (int ej = 0; ej < ny; ++ej)
    for (int ei = 0; ei < nx; ++ei) {
      const int i = s * ei, j = s * ej;
      ShellElement e;
      e.id = label("e", ei, ej);
      e.section = "s";
      e.mass = mass;
      e.nodes = {id(i, j), id(i + s, j), id(i + s, j + s), id(i, j + s)};
      if (quadratic) {
        const std::vector<NodeId> mid{id(i + 1, j), id(i + 2, j + 1), id(i + 1, j + 2), id(i, j + 1)};
        e.nodes.insert(e.nodes.end(), mid.begin(), mid.end());
      }
      pm.model.shells.push_back(e);
    }
  // As a model file gives them: the default 8-node element keeps its centre.
  if (quadratic) add_shell_centres(pm.model);
  return pm;
}

// Adds a support fixing `mask` at every node whose position satisfies `where`.
// Nodes that carry element coordinates (8-node shells' centres) are no
// places and are never supported, as a model file's selectors never take them.
inline void support_where(Model& m, const std::function<bool(const Vec3&)>& where, DofMask mask) {
  const std::vector<NodeId> coordinates = coordinate_nodes(m);
  for (const Node& n : m.nodes)
    if (where(n.x) && std::find(coordinates.begin(), coordinates.end(), n.id) == coordinates.end()) {
      // Merge with an existing support of the node, so that masks add up.
      bool merged = false;
      for (Support& s : m.supports)
        if (s.node == n.id) {
          for (size_t k = 0; k < 6; ++k) s.fixed[k] = s.fixed[k] || mask[k];
          merged = true;
        }
      if (!merged) m.supports.push_back(Support{label("n", n.id), n.id, mask});
    }
}

// Lowest `count` eigenvalues of K x = lambda M x by shift-invert subspace
// iteration with Rayleigh-Ritz, sigma below the lowest eigenvalue (K may be
// singular). Every returned pair is checked for its residual.
struct Modes {
  Eigen::VectorXd lambda;
  Eigen::MatrixXd vectors;
  Eigen::VectorXd frequencies_hz() const { return lambda.cwiseMax(0.0).cwiseSqrt() / (2.0 * pi); }
};

// Relative residual |K x - lambda M x| / (|K x| + |lambda| |M x|); rigid
// pairs (lambda ~ 0, K x ~ 0) are measured against K's diagonal instead.
inline double relative_residual(const SpMat& K, const SpMat& M, const Eigen::VectorXd& x, double lambda) {
  const Eigen::VectorXd Kx = K * x, Mx = M * x;
  const double scale =
      std::max(Kx.norm() + std::abs(lambda) * Mx.norm(), 1e-6 * K.diagonal().cwiseAbs().maxCoeff() * x.norm());
  return (Kx - lambda * Mx).norm() / scale;
}

inline Modes lowest_modes(const SpMat& K, const SpMat& M, int count, double sigma = 0.0) {
  const Eigen::Index n = K.rows();
  const Eigen::Index p = std::min<Eigen::Index>(n, std::max(2 * count, count + 8));
  const SpMat A = K - sigma * M;
  Eigen::SimplicialLDLT<SpMat> ldlt(A);
  EXPECT_EQ(ldlt.info(), Eigen::Success) << "factorization failed";

  // Deterministic, varied start vectors.
  Eigen::MatrixXd X(n, p);
  for (Eigen::Index j = 0; j < p; ++j)
    for (Eigen::Index i = 0; i < n; ++i) X(i, j) = std::sin(0.37 * static_cast<double>((i + 1) * (j + 1)));
  Eigen::VectorXd lam;
  // Eigenvalues converge twice as fast as vectors: iterate on the residuals
  // of the wanted pairs. 1e-9 is above the round-off floor that the
  // membrane-to-bending stiffness ratio sets for thin plates.
  double worst = 1.0;
  for (int it = 0; it < 2000 && worst > 1e-9; ++it) {
    const Eigen::MatrixXd Y = ldlt.solve(M * X);
    const Eigen::MatrixXd Kr = Y.transpose() * (K * Y), Mr = Y.transpose() * (M * Y);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (Kr + Kr.transpose()),
                                                                 0.5 * (Mr + Mr.transpose()));
    lam = es.eigenvalues();
    X = Y * es.eigenvectors();
    worst = 0.0;
    for (int k = 0; k < count; ++k) worst = std::max(worst, relative_residual(K, M, X.col(k), lam(k)));
  }
  EXPECT_LT(worst, 1e-7) << "subspace iteration: residual of the wanted eigenpairs";
  return Modes{lam.head(count), X.leftCols(count)};
}

// Generalized eigenvalues of an assembled model, as frequencies in Hz.
inline Eigen::VectorXd model_frequencies(const Model& m, int count, double sigma = 0.0) {
  const AssembledSystem sys = assemble(m);
  return lowest_modes(sys.K, sys.M, count, sigma).frequencies_hz();
}

// Kirchhoff plate: f = lambda / (2 pi a^2) sqrt(D / (rho t)).
inline double kirchhoff_frequency(double lambda, double a, double E, double nu, double rho, double t) {
  const double D = E * t * t * t / (12.0 * (1.0 - nu * nu));
  return lambda / (2.0 * pi * a * a) * std::sqrt(D / (rho * t));
}

}  // namespace rigflex::fe::shell_test
