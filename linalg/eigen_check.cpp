// Independent verification of eigenpairs: residuals and M-orthonormality.
#include <algorithm>
#include <cmath>

#include "linalg/block_kernels.hpp"
#include "linalg/eigen_solver.hpp"

namespace rigflex::linalg {
namespace {

double one_norm(const SpMat& A) {
  double norm = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    double column = 0.0;
    for (SpMat::InnerIterator it(A, j); it; ++it) column += std::abs(it.value());
    norm = std::max(norm, column);
  }
  return norm;
}

}  // namespace

void check_eigenpairs(const SpMat& K, const SpMat& M, EigenResult& r) {
  const Eigen::MatrixXd& X = r.vectors;
  const Eigen::Index k = X.cols();
  r.residuals.resize(k);
  r.backward_errors.resize(k);
  r.orthogonality_error = 0.0;
  if (k == 0) return;
  // The block kernel sweeps K once per 8 columns where Eigen's product
  // sweeps it once per column (2-3x slower at 20 vectors); it reads K's
  // columns as rows, which is K X for the symmetric K and M of the pencil.
  Eigen::MatrixXd KX(X.rows(), k), MX(X.rows(), k);
  detail::symmetric_times(K, X, KX);
  detail::symmetric_times(M, X, MX);
  const double k_norm = one_norm(K), m_norm = one_norm(M);
  for (Eigen::Index i = 0; i < k; ++i) {
    const double scale = std::max(KX.col(i).norm(), k_norm * X.col(i).norm() * 1e-14);
    const double residual = (KX.col(i) - r.eigenvalues[i] * MX.col(i)).norm();
    r.residuals[i] = scale > 0.0 ? residual / scale : residual;
    const double backward_scale = (k_norm + std::abs(r.eigenvalues[i]) * m_norm) * X.col(i).norm();
    r.backward_errors[i] = backward_scale > 0.0 ? residual / backward_scale : residual;
  }
  const Eigen::MatrixXd gram = X.transpose() * MX - Eigen::MatrixXd::Identity(k, k);
  r.orthogonality_error = gram.cwiseAbs().maxCoeff();
}

}  // namespace rigflex::linalg
