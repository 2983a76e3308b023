#pragma once
// A scale of the upper spectrum of the pencil (K, M), used to choose the
// default shift and to balance K + s M in the mechanism diagnosis.
#include "linalg/sparse_cholesky.hpp"

namespace rigflex::linalg {

// s = sum(K_ii) / sum(M_ii) over the DOFs with M_ii > 0: the mass-weighted
// mean of the diagonal Rayleigh quotients K_ii / M_ii. Returns 1 when that
// is not positive (no mass at all, or no stiffness on massed DOFs).
inline double pencil_scale(const SpMat& K, const SpMat& M) {
  const Eigen::VectorXd k = K.diagonal();
  const Eigen::VectorXd m = M.diagonal();
  double sum_k = 0.0, sum_m = 0.0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    if (m[i] > 0.0) {
      sum_k += k[i];
      sum_m += m[i];
    }
  }
  const double s = sum_m > 0.0 ? sum_k / sum_m : 0.0;
  return s > 0.0 ? s : 1.0;
}

}  // namespace rigflex::linalg
