#pragma once
// Test pencils with known or independently computable spectra, and the
// checks shared by the eigen solver tests.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "linalg/eigen_solver.hpp"

namespace rigflex::linalg::testing {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

struct Pencil {
  SpMat K;
  SpMat M;
};

inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

inline SpMat diagonal_matrix(const VectorXd& d) {
  SpMat D(d.size(), d.size());
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < d.size(); ++i) t.emplace_back(i, i, d[i]);
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

// K = B'B + 0.05 I with B sparse random (three off-diagonal couplings per
// column plus a unit diagonal): sparse, SPD, eigenvalues simple in practice.
inline SpMat random_spd(Index n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Triplet<double>> t;
  for (Index j = 0; j < n; ++j) {
    t.emplace_back(j, j, 1.0);
    for (int e = 0; e < 3; ++e) {
      t.emplace_back(static_cast<Index>(rng() % static_cast<std::uint64_t>(n)), j,
                     uniform(rng, -1.0, 1.0));
    }
  }
  SpMat B(n, n);
  B.setFromTriplets(t.begin(), t.end());
  SpMat I(n, n);
  I.setIdentity();
  return SpMat(SpMat(B.transpose()) * B) + 0.05 * I;
}

// Random SPD K, diagonal M in [0.5, 2]; every third DOF massless if asked.
inline Pencil random_pencil(Index n, std::uint64_t seed, bool singular_mass) {
  std::mt19937_64 rng(seed + 1000);
  VectorXd m(n);
  for (Index i = 0; i < n; ++i) m[i] = (singular_mass && i % 3 == 2) ? 0.0 : uniform(rng, 0.5, 2.0);
  return {random_spd(n, seed), diagonal_matrix(m)};
}

// n masses m between springs k: fixed at both ends (K = k tridiag(-1,2,-1))
// or free-free (end diagonals k, one rigid-body mode).
inline Pencil spring_chain(Index n, double k, double m, bool free_free) {
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < n; ++i) {
    const bool end = i == 0 || i == n - 1;
    t.emplace_back(i, i, (free_free && end) ? k : 2.0 * k);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -k);
      t.emplace_back(i + 1, i, -k);
    }
  }
  SpMat K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return {K, diagonal_matrix(VectorXd::Constant(n, m))};
}

// Free 3D truss lattice: nodes on an nx x ny x nz integer grid, bars (EA = 1)
// between all nodes of a unit cell (edges, face and body diagonals), unit
// lumped masses with a deterministic +-30 % variation. Six rigid-body modes.
inline Pencil free_lattice(int nx, int ny, int nz) {
  const Index nodes = static_cast<Index>(nx) * ny * nz;
  auto id = [&](int x, int y, int z) { return static_cast<Index>((z * ny + y) * nx + x); };
  std::vector<Eigen::Triplet<double>> t;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        for (int dz = 0; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              // each unordered pair once: lexicographically positive offsets
              if (dz == 0 && (dy < 0 || (dy == 0 && dx <= 0))) continue;
              const int x2 = x + dx, y2 = y + dy, z2 = z + dz;
              if (x2 < 0 || x2 >= nx || y2 < 0 || y2 >= ny || z2 >= nz) continue;
              const Eigen::Vector3d d(dx, dy, dz);
              const double length = d.norm();
              const Eigen::Matrix3d k = d * d.transpose() / (length * length * length);
              const Index a = id(x, y, z), b = id(x2, y2, z2);
              for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) {
                  t.emplace_back(3 * a + i, 3 * a + j, k(i, j));
                  t.emplace_back(3 * b + i, 3 * b + j, k(i, j));
                  t.emplace_back(3 * a + i, 3 * b + j, -k(i, j));
                  t.emplace_back(3 * b + i, 3 * a + j, -k(i, j));
                }
            }
  SpMat K(3 * nodes, 3 * nodes);
  K.setFromTriplets(t.begin(), t.end());
  VectorXd m(3 * nodes);
  for (Index a = 0; a < nodes; ++a) m.segment(3 * a, 3).setConstant(1.0 + 0.3 * std::sin(1.7 * a));
  return {K, diagonal_matrix(m)};
}

// K = G Q D Q' G', M = G G' (G = I when !congruence): the eigenvalues of the
// pencil are exactly `values` (with their multiplicities).
inline Pencil prescribed_spectrum(const VectorXd& values, std::uint64_t seed, bool congruence) {
  const Index n = values.size();
  std::mt19937_64 rng(seed);
  MatrixXd A(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) A(i, j) = uniform(rng, -1.0, 1.0);
  const MatrixXd Q = Eigen::HouseholderQR<MatrixXd>(A).householderQ();
  MatrixXd K = Q * values.asDiagonal() * Q.transpose();
  MatrixXd M = MatrixXd::Identity(n, n);
  if (congruence) {
    MatrixXd G = MatrixXd::Identity(n, n);
    for (Index i = 1; i < n; ++i) G(i, i - 1) = uniform(rng, -0.5, 0.5);
    K = G * K * G.transpose();
    M = G * G.transpose();
  }
  K = 0.5 * (K + K.transpose()).eval();
  M = 0.5 * (M + M.transpose()).eval();
  return {K.sparseView(), M.sparseView()};
}

// Graph Laplacian of an nx x ny grid (free edges, one zero eigenvalue),
// M = I. Eigenvalues 4 sin^2(i pi / 2nx) + 4 sin^2(j pi / 2ny); a square grid
// has every i != j value twice.
inline Pencil grid_laplacian(Index nx, Index ny) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [&](Index x, Index y) { return y * nx + x; };
  auto bond = [&](Index a, Index b) {
    t.emplace_back(a, a, 1.0);
    t.emplace_back(b, b, 1.0);
    t.emplace_back(a, b, -1.0);
    t.emplace_back(b, a, -1.0);
  };
  for (Index y = 0; y < ny; ++y)
    for (Index x = 0; x < nx; ++x) {
      if (x + 1 < nx) bond(id(x, y), id(x + 1, y));
      if (y + 1 < ny) bond(id(x, y), id(x, y + 1));
    }
  SpMat K(nx * ny, nx * ny);
  K.setFromTriplets(t.begin(), t.end());
  return {K, diagonal_matrix(VectorXd::Ones(nx * ny))};
}

inline VectorXd grid_laplacian_eigenvalues(Index nx, Index ny, Index count) {
  std::vector<double> all;
  for (Index i = 0; i < nx; ++i)
    for (Index j = 0; j < ny; ++j) {
      const double a = std::sin(static_cast<double>(i) * std::numbers::pi / (2.0 * static_cast<double>(nx)));
      const double b = std::sin(static_cast<double>(j) * std::numbers::pi / (2.0 * static_cast<double>(ny)));
      all.push_back(4.0 * a * a + 4.0 * b * b);
    }
  std::sort(all.begin(), all.end());
  return Eigen::Map<VectorXd>(all.data(), count);
}

// Residual and M-orthonormality of every returned pair (recomputed here,
// independently of the solver's own check). Pairs with |lambda| <=
// rigid_below are rigid-body modes: K x is pure rounding for them,
// ~1e-16 ||K||_1 ||x||, so against the residual's floor 1e-14 ||K||_1 ||x||
// they read ~1e-2 however exact they are; they are held to residual <= 1,
// i.e. ||K x - lambda M x|| <= 1e-14 ||K||_1 ||x|| (about 50 ulps).
inline void expect_valid_pairs(const Pencil& p, const EigenResult& r, double residual_tol,
                               double orthogonality_tol, double rigid_below = -1.0) {
  EigenResult copy = r;
  check_eigenpairs(p.K, p.M, copy);
  ASSERT_EQ(copy.residuals.size(), r.eigenvalues.size());
  for (Index i = 0; i < copy.residuals.size(); ++i) {
    const bool rigid = std::abs(r.eigenvalues[i]) <= rigid_below;
    EXPECT_LE(copy.residuals[i], rigid ? 1.0 : residual_tol)
        << "pair " << i << ", lambda " << r.eigenvalues[i];
  }
  EXPECT_LE(copy.orthogonality_error, orthogonality_tol);
  // Normwise backward error: bounded by the residual ratio above (||K x|| <=
  // ||K||_1 ||x||) and, for rigid-body modes, by 1e-14 times it; pairs
  // correct to working precision sit far below 1e-10.
  ASSERT_EQ(copy.backward_errors.size(), r.eigenvalues.size());
  for (Index i = 0; i < copy.backward_errors.size(); ++i) EXPECT_LE(copy.backward_errors[i], 1e-10);
  for (Index i = 1; i < r.eigenvalues.size(); ++i) EXPECT_LE(r.eigenvalues[i - 1], r.eigenvalues[i]);
}

// |a_i - b_i| <= rel * max(|b_i|, floor) for every i.
inline void expect_same_eigenvalues(const VectorXd& a, const VectorXd& b, double rel, double floor) {
  ASSERT_EQ(a.size(), b.size());
  for (Index i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], b[i], rel * std::max(std::abs(b[i]), floor)) << "eigenvalue " << i;
  }
}

// Eigenvectors agree as invariant subspaces: for each cluster of eigenvalues
// (relative spacing below cluster_gap), the singular values of X_a' M X_b
// (cosines of the principal angles) are all >= 1 - tol. Clusters cut by the
// end of the list are skipped (their partners were not computed).
inline void expect_same_subspaces(const Pencil& p, const EigenResult& a, const EigenResult& b,
                                  double cluster_gap, double tol, double zero_floor) {
  const Index k = std::min(a.eigenvalues.size(), b.eigenvalues.size());
  const MatrixXd MB = p.M * b.vectors;
  Index begin = 0;
  while (begin < k) {
    Index end = begin + 1;
    auto close = [&](Index i, Index j) {
      const double scale = std::max({std::abs(b.eigenvalues[i]), std::abs(b.eigenvalues[j]), zero_floor});
      return std::abs(b.eigenvalues[j] - b.eigenvalues[i]) <= cluster_gap * scale;
    };
    while (end < b.eigenvalues.size() && close(end - 1, end)) ++end;
    if (end > k) break;
    const MatrixXd cosines =
        a.vectors.middleCols(begin, end - begin).transpose() * MB.middleCols(begin, end - begin);
    Eigen::JacobiSVD<MatrixXd> svd(cosines);
    EXPECT_GE(svd.singularValues().minCoeff(), 1.0 - tol)
        << "cluster " << begin << ".." << end - 1 << " at lambda " << b.eigenvalues[begin];
    begin = end;
  }
}

}  // namespace rigflex::linalg::testing
