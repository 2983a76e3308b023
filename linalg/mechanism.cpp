// Null space of a symmetric positive semidefinite matrix by block inverse
// iteration on a slightly regularized, diagonally scaled copy.
#include "linalg/mechanism.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "linalg/pencil_scale.hpp"
#include "linalg/random_block.hpp"

namespace rigflex::linalg {
namespace {

// B = D^-1/2 A D^-1/2 has a unit diagonal; B + 1e-12 I is positive definite
// (rounding in its Cholesky is ~1e-16 per unit of diagonal), and inverse
// iteration on it damps every direction with Rayleigh quotient mu >= 1e-8
// by mu / 1e-12 >= 1e4 per step relative to the null space: four steps leave
// such directions below 1e-16.
constexpr double kRegularization = 1e-12;
constexpr int kInverseIterations = 4;
// Null directions have Rayleigh quotients at rounding level (~1e-16 n);
// a legitimately soft direction of a scaled FE matrix sits at ~1e-8 or above
// even for penalty stiffnesses 1e8 times the rest.
constexpr double kNullRayleighQuotient = 1e-10;
constexpr double kMovingFraction = 0.05;
constexpr Eigen::Index kInitialBlock = 4;

Eigen::MatrixXd orthonormal_basis(const Eigen::MatrixXd& X) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(X);
  return qr.householderQ() * Eigen::MatrixXd::Identity(X.rows(), X.cols());
}

struct ScaledMatrix {
  SpMat B;                            // D^-1/2 A D^-1/2 on the kept DOFs
  Eigen::VectorXd scale;              // D^-1/2
  std::vector<Eigen::Index> kept;     // kept -> original index
  std::vector<Eigen::Index> zero_rows;
};

ScaledMatrix scale_nonzero_rows(const SpMat& A) {
  ScaledMatrix s;
  const Eigen::Index n = A.rows();
  std::vector<Eigen::Index> new_index(static_cast<size_t>(n), -1);
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    bool nonzero = false;
    for (SpMat::InnerIterator it(A, j); it; ++it) {
      if (it.value() != 0.0) nonzero = true;
      if (it.row() == j) diag[j] = it.value();
    }
    if (nonzero) {
      new_index[static_cast<size_t>(j)] = static_cast<Eigen::Index>(s.kept.size());
      s.kept.push_back(j);
    } else {
      s.zero_rows.push_back(j);
    }
  }
  const auto nk = static_cast<Eigen::Index>(s.kept.size());
  s.scale.resize(nk);
  for (Eigen::Index k = 0; k < nk; ++k) {
    const double d = std::abs(diag[s.kept[static_cast<size_t>(k)]]);
    s.scale[k] = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(A.nonZeros()));
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index nj = new_index[static_cast<size_t>(j)];
    if (nj < 0) continue;
    for (SpMat::InnerIterator it(A, j); it; ++it) {
      const Eigen::Index ni = new_index[static_cast<size_t>(it.row())];
      if (ni >= 0) triplets.emplace_back(ni, nj, it.value() * s.scale[ni] * s.scale[nj]);
    }
  }
  s.B.resize(nk, nk);
  s.B.setFromTriplets(triplets.begin(), triplets.end());
  return s;
}

// Factorizes B + eps I, raising eps if rounding makes it fail; false if B is
// too far from semidefinite to be diagnosed.
bool factorize_regularized(const SpMat& B, SparseCholesky& factor) {
  SpMat identity(B.rows(), B.cols());
  identity.setIdentity();
  for (double eps = kRegularization; eps <= 1e-6; eps *= 100.0) {
    if (factor.factorize(SpMat(B + eps * identity)).ok) return true;
  }
  return false;
}

// Orthonormal basis (in the scaled coordinates) of the numerical null space
// of B, by block inverse iteration and a Rayleigh-Ritz projection; the block
// grows until it holds at least one direction that is not null.
Eigen::MatrixXd null_space_basis(const SpMat& B, SparseCholesky& factor) {
  const Eigen::Index n = B.rows();
  RandomBlocks random(0x6d656368616e69ULL);
  for (Eigen::Index p = std::min(n, kInitialBlock);; p = std::min(n, 2 * p)) {
    Eigen::MatrixXd X = orthonormal_basis(random.next(n, p));
    for (int it = 0; it < kInverseIterations; ++it) X = orthonormal_basis(factor.solve(X));
    Eigen::MatrixXd H = X.transpose() * (B * X);
    H = 0.5 * (H + H.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
    Eigen::Index null_count = 0;
    while (null_count < p && eig.eigenvalues()[null_count] <= kNullRayleighQuotient) ++null_count;
    if (null_count < p || p == n) return X * eig.eigenvectors().leftCols(null_count);
  }
}

}  // namespace

std::vector<Eigen::Index> mechanism_dofs(const SpMat& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("mechanism_dofs: matrix must be square");
  const ScaledMatrix s = scale_nonzero_rows(A);
  std::vector<Eigen::Index> dofs = s.zero_rows;
  if (!s.kept.empty()) {
    SparseCholesky factor;
    if (factorize_regularized(s.B, factor)) {
      const Eigen::MatrixXd null_scaled = null_space_basis(s.B, factor);
      if (null_scaled.cols() > 0) {
        // Back to physical coordinates, x = D^-1/2 x_scaled, then an
        // orthonormal basis there: its row norms do not depend on the basis.
        const Eigen::MatrixXd physical = orthonormal_basis(s.scale.asDiagonal() * null_scaled);
        const Eigen::VectorXd weight = physical.rowwise().norm();
        const double threshold = kMovingFraction * weight.maxCoeff();
        for (Eigen::Index k = 0; k < weight.size(); ++k) {
          if (weight[k] > threshold) dofs.push_back(s.kept[static_cast<size_t>(k)]);
        }
      }
    }
  }
  std::sort(dofs.begin(), dofs.end());
  return dofs;
}

std::vector<Eigen::Index> mechanism_dofs(const SpMat& K, const SpMat& M) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    throw std::invalid_argument("mechanism_dofs: K and M must be square and of equal size");
  }
  return mechanism_dofs(SpMat(K + pencil_scale(K, M) * M));
}

}  // namespace rigflex::linalg
