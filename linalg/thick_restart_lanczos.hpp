#pragma once
// Internal: the shift-invert thick-restart Lanczos iteration behind
// solve_lanczos (see thick_restart_lanczos.cpp for the method).
#include <Eigen/Core>
#include <functional>
#include <string>

#include "linalg/eigen_solver.hpp"
#include "linalg/sparse_cholesky.hpp"

namespace rigflex::linalg::detail {

struct LanczosSettings {
  Eigen::Index count = 0;
  Eigen::Index basis = 0;  // m, basis size before a restart
  Eigen::Index block = 1;  // b
  double tolerance = 0;
  int max_restarts = 0;
  bool verify = true;  // multiplicity check after convergence
  unsigned seed = 1;
  const std::function<void(const EigenProgress&)>* progress = nullptr;
};

struct LanczosOutcome {
  Eigen::MatrixXd X;  // purified Ritz vectors of the leading converged pairs, theta descending
  bool converged = false;
  std::string message;
  int restarts = 0;
  long applications = 0;  // of Op to a vector
  // When not converged: the last Ritz values of Op (descending) and their
  // residual norms, for diagnose_stall.
  Eigen::VectorXd theta, residual;
};

// Lowest `count` eigenvectors of the pencil whose K - sigma M is factorized
// in `factor`, as purified Ritz vectors (not yet M-orthonormalized).
LanczosOutcome thick_restart_lanczos(const SpMat& M, SparseCholesky& factor,
                                     const LanczosSettings& settings);

}  // namespace rigflex::linalg::detail
