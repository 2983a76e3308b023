#include "linalg/eigen_postprocess.hpp"

#include <Eigen/Eigenvalues>

namespace rigflex::linalg {

Eigen::VectorXd rayleigh_ritz(const SpMat& K, const SpMat& M, Eigen::MatrixXd& X) {
  if (X.cols() == 0) return Eigen::VectorXd();
  Eigen::MatrixXd Kr = X.transpose() * (K * X);
  Eigen::MatrixXd Mr = X.transpose() * (M * X);
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Mr = 0.5 * (Mr + Mr.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kr, Mr);
  X = (X * eig.eigenvectors()).eval();  // eigenvectors are Mr-orthonormal
  return eig.eigenvalues();
}

void normalize_signs(Eigen::MatrixXd& X) {
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    Eigen::Index largest = 0;
    X.col(j).cwiseAbs().maxCoeff(&largest);
    if (X(largest, j) < 0.0) X.col(j) = -X.col(j);
  }
}

}  // namespace rigflex::linalg
