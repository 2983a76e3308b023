#pragma once
// Steps shared by the eigen solvers once they have approximate eigenvectors.
#include <Eigen/Core>

#include "linalg/sparse_cholesky.hpp"

namespace rigflex::linalg {

// Rayleigh-Ritz on the pencil in span(X): replaces X by the M-orthonormal
// Ritz vectors of (X'KX, X'MX) and returns their Ritz values, ascending.
// The values are Rayleigh quotients, accurate to the square of the vectors'
// error, which is better than the 1/nu of the transformed problem.
Eigen::VectorXd rayleigh_ritz(const SpMat& K, const SpMat& M, Eigen::MatrixXd& X);

// Makes the largest-|component| entry of each column positive (the first
// such entry on ties), so that results do not depend on arbitrary signs.
void normalize_signs(Eigen::MatrixXd& X);

}  // namespace rigflex::linalg
