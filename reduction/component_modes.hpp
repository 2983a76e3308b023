#pragma once
// Guyan and Craig-Bampton reduction as pure functions of matrices:
// (K, M, boundary DOFs, options) -> ReducedMatrices.
//
// With the DOFs split into boundary b (retained) and interior i:
//   constraint modes  Psi = -K_ii^-1 K_ib        (one factorization of K_ii)
//   Guyan             T = [I; Psi]
//   Craig-Bampton     T = [I 0; Psi Phi], Phi the lowest fixed-interface
//                     modes K_ii Phi = M_ii Phi Omega^2, Phi' M_ii Phi = I,
//                     from the shift-invert Lanczos on the SAME factorization
//                     of K_ii (shift 0: K_ii is positive definite whenever
//                     the boundary holds the structure statically).
//   K_r = T' K T, M_r = T' M T. The stiffness is formed blockwise as
//   [K_bb + K_bi Psi, 0; 0, Omega^2]: exact in exact arithmetic, and free of
//   the rounding that T' K T leaves in the coupling block.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "linalg/eigen_solver.hpp"
#include "reduction/reduced_model.hpp"
#include "linalg/sparse_cholesky.hpp"

namespace rigflex::reduction {

struct ComponentModeOptions {
  ReductionMethod method = ReductionMethod::guyan;
  // Craig-Bampton: the number of fixed-interface modes, or all modes below
  // cutoff_hz (exactly one of the two for craig-bampton; neither for guyan).
  int modes = 0;
  std::optional<double> cutoff_hz;
  // Keep T (full DOFs x reduced coordinates) in the result, to expand
  // reduced vectors (checks, mode shapes). Costs n x (nb + nm) doubles.
  bool keep_basis = true;
  double tolerance = 1e-10;  // of the fixed-interface eigenpairs (EigenOptions::tolerance)
  std::function<void(const linalg::EigenProgress&)> progress;  // optional
  // K_ii's factorization is not attempted when CHOLMOD's analysis puts the
  // factor above max_factor_bytes (0: no limit): over_memory_limit.
  // `analyzed` (optional) hears that analysis before the numeric work.
  double max_factor_bytes = 0;
  std::function<void(const linalg::FactorStatistics&)> analyzed;
  // Craig-Bampton's fixed-interface modes by another solver (empty: the
  // built-in Lanczos on the factorization of K_ii that the constraint modes
  // use; the MPI backend factorizes K_ii again, distributed).
  linalg::EigenBackend eigen_backend;

  // Throws std::invalid_argument naming the option: negative or missing mode
  // count, both count and cutoff, more modes than interior DOFs, cutoff <= 0.
  void validate(Eigen::Index interior_dofs) const;
};

struct ComponentModeStatistics {
  double partition_seconds = 0;  // extracting K_ii, K_ib, ...
  double factor_seconds = 0;     // analysis + factorization of K_ii
  double constraint_seconds = 0; // the nb solves for Psi
  double eigen_seconds = 0;      // fixed-interface modes (Craig-Bampton)
  double projection_seconds = 0; // T' M T and the blocks of K
  double factor_bytes = 0;       // memory of the factor of K_ii
  long solves = 0;               // right-hand sides solved with K_ii
};

struct ReducedMatrices {
  bool ok = false;
  std::string message;  // why not ok
  bool over_memory_limit = false;  // refused by ComponentModeOptions::max_factor_bytes
  // Free DOFs (indices into K) where K_ii was found singular: the interior
  // is a mechanism once the boundary is held (for example a floating frame
  // whose interface cannot hold it statically).
  std::vector<Eigen::Index> mechanism_dofs;
  Eigen::MatrixXd K, M;              // reduced, symmetric
  Eigen::MatrixXd basis;             // T, if kept: rows = K.rows(), boundary rows are unit rows
  Eigen::VectorXd mode_eigenvalues;  // Omega^2 of the fixed-interface modes kept, (rad/s)^2
  linalg::EigenResult modes_result;          // the Lanczos outcome (Craig-Bampton), residuals etc.
  ComponentModeStatistics statistics;
};

// boundary: distinct free-DOF indices into K, in the order of the reduced
// coordinates. Throws std::invalid_argument for invalid options, an empty,
// out-of-range or repeated boundary, or mismatched K and M; numerical
// outcomes (a singular K_ii, modes that do not converge) come back in the
// result with ok = false.
ReducedMatrices reduce_component(const linalg::SpMat& K, const linalg::SpMat& M, const std::vector<Eigen::Index>& boundary,
                                 const ComponentModeOptions& options);

}  // namespace rigflex::reduction
