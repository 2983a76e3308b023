// Dense reference solver for small models: shift-invert reduction of the
// pencil to a standard symmetric eigenproblem.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "linalg/eigen_postprocess.hpp"
#include "linalg/eigen_solver.hpp"
#include "linalg/mechanism.hpp"

namespace rigflex::linalg {
namespace {

double min_relative_pivot(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& C) {
  double ratio = std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd& L = llt.matrixLLT();
  for (Eigen::Index j = 0; j < C.rows(); ++j) {
    ratio = std::min(ratio, C(j, j) > 0.0 ? L(j, j) * L(j, j) / C(j, j) : 0.0);
  }
  return ratio;
}

// Number of finite eigenvalues: n minus the numerical nullity of M, decided
// on M itself (well scaled) rather than on nu, whose range spans the whole
// conditioning of K - sigma M.
Eigen::Index finite_count(const Eigen::MatrixXd& M) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M, Eigen::EigenvaluesOnly);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  const double tiny = 100.0 * static_cast<double>(M.rows()) *
                      std::numeric_limits<double>::epsilon() * largest;
  return (eig.eigenvalues().array() > tiny).count();
}

void validate(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, double shift) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    throw std::invalid_argument("solve_dense: K and M must be square and of equal size");
  }
  if (count < 1 || count > K.rows()) {
    throw std::invalid_argument("solve_dense: count must lie in [1, n] (got " +
                                std::to_string(count) + ")");
  }
  if (!std::isfinite(shift)) throw std::invalid_argument("solve_dense: shift must be finite");
}

}  // namespace

EigenResult solve_dense(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, double shift) {
  validate(K, M, count, shift);
  const auto start = std::chrono::steady_clock::now();
  EigenResult r;
  r.requested = count;
  r.shift = shift;
  const Eigen::MatrixXd C = K - shift * M;
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  const bool factored = llt.info() == Eigen::Success;
  if (!factored || min_relative_pivot(llt, C) < kTinyPivot) {
    r.mechanism_dofs = mechanism_dofs(SpMat(K.sparseView()), SpMat(M.sparseView()));
    if (!r.mechanism_dofs.empty()) {
      r.message = "K - sigma M is singular: mechanism (" + std::to_string(r.mechanism_dofs.size()) +
                  " DOFs move with neither stiffness nor mass; see mechanism_dofs)";
      return r;
    }
    if (!factored) {
      r.message = "K - sigma M is not positive definite at sigma = " + std::to_string(shift) +
                  ": the shift must lie below the lowest eigenvalue";
      return r;
    }
  }
  // A = L^-1 M L^-T, nu = 1 / (lambda - shift); x = L^-T y / sqrt(nu) is
  // M-normalized because x' M x = y' A y = nu.
  Eigen::MatrixXd A = llt.matrixL().solve(M);
  A = llt.matrixL().solve(A.transpose().eval());
  A = 0.5 * (A + A.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  const Eigen::Index n = K.rows();
  const Eigen::Index available = std::min<Eigen::Index>(count, finite_count(M));
  Eigen::Index k = 0;
  while (k < available && eig.eigenvalues()[n - 1 - k] > 0.0) ++k;
  Eigen::MatrixXd X(n, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    X.col(i) = eig.eigenvectors().col(n - 1 - i) / std::sqrt(eig.eigenvalues()[n - 1 - i]);
  }
  X = llt.matrixU().solve(X);
  const SpMat Ks = K.sparseView(), Ms = M.sparseView();
  r.eigenvalues = rayleigh_ritz(Ks, Ms, X);
  normalize_signs(X);
  r.vectors = std::move(X);
  r.converged_count = static_cast<int>(k);
  r.converged = k == count;
  r.message = r.converged ? "converged"
                          : "only " + std::to_string(k) + " finite eigenvalues (M is singular)";
  r.iteration_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  check_eigenpairs(Ks, Ms, r);
  return r;
}

}  // namespace rigflex::linalg
