// solve_lanczos: the eigen solver's entry points. Factorization of the
// shifted pencil (pencil_factorization.cpp), the iteration
// (thick_restart_lanczos.cpp), then a Rayleigh-Ritz step on the pencil and
// the independent check of every pair.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "linalg/block_kernels.hpp"
#include "linalg/eigen_postprocess.hpp"
#include "linalg/eigen_solver.hpp"
#include "linalg/lanczos_stall.hpp"
#include "linalg/pencil_scale.hpp"
#include "linalg/stopwatch.hpp"
#include "linalg/thick_restart_lanczos.hpp"

namespace rigflex::linalg {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

detail::LanczosSettings settings_from(const EigenOptions& options, Index n, const SparseCholesky& factor) {
  detail::LanczosSettings s;
  s.count = options.count;
  s.block = options.resolved_block(n, factor.statistics().factor_nnz);
  s.basis = options.resolved_subspace(n, static_cast<int>(s.block));
  s.tolerance = options.tolerance;
  s.max_restarts = options.max_restarts;
  s.verify = options.verify_multiplicities;
  s.seed = options.seed;
  s.progress = &options.progress;
  return s;
}

void check_sizes(const SpMat& K, const SpMat& M) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    throw std::invalid_argument("solve_lanczos: K and M must be square and of equal size");
  }
}

bool use_dense(const EigenOptions& options, Index n) {
  return options.method == EigenMethod::dense ||
         (options.method == EigenMethod::automatic && n <= options.dense_threshold);
}

// The iteration on a checked factorization; the pairs are not yet
// post-processed (see finish).
EigenResult iterate(const SpMat& K, const SpMat& M, const EigenOptions& options,
                    SparseCholesky& factor_at_shift) {
  check_sizes(K, M);
  options.validate(K.rows());
  if (!factor_at_shift.factorized() || factor_at_shift.rows() != K.rows()) {
    throw std::invalid_argument("solve_lanczos: the factorization does not match K - sigma M");
  }
  const std::optional<double> factored = factor_at_shift.shift();
  if (!factored && !options.shift) {
    throw std::invalid_argument("solve_lanczos: the shift of the factorization is unknown");
  }
  if (factored && options.shift && *factored != *options.shift) {
    throw std::invalid_argument("solve_lanczos: options.shift differs from the factorization's shift");
  }
  const auto start = std::chrono::steady_clock::now();
  EigenResult r;
  r.requested = options.count;
  r.shift = factored ? *factored : *options.shift;
  const detail::LanczosSettings settings = settings_from(options, K.rows(), factor_at_shift);
  r.block_size = static_cast<int>(settings.block);
  detail::LanczosOutcome outcome = detail::thick_restart_lanczos(M, factor_at_shift, settings);
  r.vectors = std::move(outcome.X);
  r.converged = outcome.converged;
  r.message = std::move(outcome.message);
  r.restarts = outcome.restarts;
  r.operator_applications = outcome.applications;
  if (!r.converged && outcome.theta.size() > 0) {
    StallFacts facts;
    facts.shift = r.shift;
    facts.theta = std::move(outcome.theta);
    facts.residual = std::move(outcome.residual);
    facts.count = options.count;
    facts.converged = static_cast<int>(r.vectors.cols());
    facts.basis = static_cast<int>(settings.basis);
    facts.block = static_cast<int>(settings.block);
    facts.restarts = r.restarts;
    facts.scale = pencil_scale(K, M);
    r.stall = diagnose_stall(facts);
    r.message += ": " + r.stall.why + "; " + r.stall.advice;
  }
  r.iteration_seconds = seconds_since(start);
  return r;
}

// The retry on the same factor for a cluster or slow convergence: four
// times the basis (at least room for two copies of the cluster beside the
// wanted pairs), a block as large as the cluster up to 8 (a block Lanczos
// of block b resolves b close eigenvalues together), a fresh start vector.
// Why four: on 700 eigenvalues spread over 1 % below the wanted boundary
// (tests/linalg/test_lanczos_stall.cpp) twice the basis stalled at the same
// pairs, four times converged; a Krylov space grows its polynomial filter
// faster than linearly with the basis between restarts. None when the basis
// cannot grow or it and the factor would exceed the memory the caller allowed.
std::optional<EigenOptions> retry_on_factor(const EigenOptions& options, const EigenResult& r, Index n,
                                            double factor_nnz) {
  if (r.stall.cause != StallCause::clustered && r.stall.cause != StallCause::slow_convergence) return std::nullopt;
  const int basis = options.resolved_subspace(n, r.block_size);
  const int block = retry_block(r.stall, r.block_size);
  const long grown = std::min<long>(retry_basis(r.stall, options.count, basis, r.block_size), n);
  if (grown <= basis) return std::nullopt;
  const double bytes = 8.0 * (static_cast<double>(n) * static_cast<double>(grown + block) + factor_nnz);
  if (options.max_factor_bytes > 0 && bytes > options.max_factor_bytes) return std::nullopt;
  EigenOptions retry = options;
  retry.shift = r.shift;
  retry.subspace = static_cast<int>(grown);
  retry.block_size = grown >= options.count + 2L * block ? block : 1;
  retry.seed = options.seed + 1;
  return retry;
}

// Keeps the retry's result where it converged or got further, else the
// first one's; the counts of work add up either way.
EigenResult take_retry(EigenResult first, EigenResult retry) {
  const bool better = retry.converged || retry.vectors.cols() > first.vectors.cols();
  EigenResult& kept = better ? retry : first;
  const EigenResult& other = better ? first : retry;
  kept.restarts += other.restarts;
  kept.operator_applications += other.operator_applications;
  kept.iteration_seconds += other.iteration_seconds;
  kept.retries = first.retries + 1;
  if (better) {
    kept.first_attempt = first.message;
  } else {
    kept.message += " (an automatic retry did not get further: " + retry.message + ")";
  }
  return std::move(kept);
}

EigenResult iterate_with_retry(const SpMat& K, const SpMat& M, const EigenOptions& options,
                               SparseCholesky& factor_at_shift) {
  EigenResult r = iterate(K, M, options, factor_at_shift);
  if (r.converged || !options.automatic_retry) return r;
  if (const std::optional<EigenOptions> retry =
          retry_on_factor(options, r, K.rows(), factor_at_shift.statistics().factor_nnz)) {
    return take_retry(std::move(r), iterate(K, M, *retry, factor_at_shift));
  }
  return r;
}

// Rayleigh-Ritz on the pencil in span(X) (see rayleigh_ritz in
// eigen_postprocess.hpp), with the products in the block kernels: K X for
// 20 vectors in three sweeps over K (K symmetric, both triangles stored)
// instead of Eigen's twenty. Replaces X by the M-orthonormal Ritz vectors;
// returns the Ritz values, ascending.
Eigen::VectorXd block_rayleigh_ritz(const SpMat& K, const SpMat& M, MatrixXd& X) {
  const Index k = X.cols();
  if (k == 0) return Eigen::VectorXd();
  const detail::SerialBlas serial;  // skinny products: threads only cost
  MatrixXd product(X.rows(), k), Kr(k, k), Mr(k, k);
  detail::symmetric_times(K, X, product);
  detail::gemm(true, X, product, 1.0, 0.0, Kr);
  detail::symmetric_times(M, X, product);
  detail::gemm(true, X, product, 1.0, 0.0, Mr);
  product = MatrixXd();
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Mr = 0.5 * (Mr + Mr.transpose()).eval();
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(Kr, Mr);
  // X = X V (V is Mr-orthonormal) in place, a slice of rows at a time.
  constexpr Index kRows = 2048;
  MatrixXd slice;
  for (Index row = 0; row < X.rows(); row += kRows) {
    const Index rows = std::min(kRows, X.rows() - row);
    slice.resize(rows, k);
    detail::gemm(false, X.middleRows(row, rows), eig.eigenvectors(), 1.0, 0.0, slice);
    X.middleRows(row, rows) = slice;
  }
  return eig.eigenvalues();
}

// Rayleigh-Ritz on the pencil and the independent check of every pair. It
// needs K and M only: the one-call form runs it after releasing its factor,
// whose memory would otherwise add to the temporaries of these products.
void finish(const SpMat& K, const SpMat& M, EigenResult& r) {
  const auto start = std::chrono::steady_clock::now();
  r.eigenvalues = block_rayleigh_ritz(K, M, r.vectors);
  normalize_signs(r.vectors);
  r.converged_count = static_cast<int>(r.eigenvalues.size());
  r.iteration_seconds += seconds_since(start);
  check_eigenpairs(K, M, r);
}

}  // namespace

EigenResult solve_lanczos(const SpMat& K, const SpMat& M, const EigenOptions& options,
                          SparseCholesky& factor_at_shift) {
  EigenResult r = iterate_with_retry(K, M, options, factor_at_shift);
  finish(K, M, r);
  return r;
}

EigenResult solve_lanczos(const SpMat& K, const SpMat& M, const EigenOptions& options) {
  check_sizes(K, M);
  options.validate(K.rows());
  if (use_dense(options, K.rows())) {
    const double sigma = options.shift ? *options.shift : default_shift(K, M);
    return solve_dense(MatrixXd(K), MatrixXd(M), options.count, sigma);
  }
  const auto start = std::chrono::steady_clock::now();
  auto factor = std::make_unique<SparseCholesky>();
  factor->set_memory_limit(options.max_factor_bytes);
  if (options.analyzed) factor->on_analysis(options.analyzed);
  const PencilFactorization pencil = factorize_pencil(K, M, options.shift, *factor);
  const double factor_seconds = seconds_since(start);
  if (!pencil.ok) {
    EigenResult r;
    r.requested = options.count;
    r.shift = pencil.shift;
    r.message = pencil.message;
    r.mechanism_dofs = pencil.mechanism_dofs;
    r.over_memory_limit = pencil.status.over_memory_limit;
    r.factor_seconds = factor_seconds;
    return r;
  }
  EigenOptions at_shift = options;
  at_shift.shift = pencil.shift;
  EigenResult r = iterate_with_retry(K, M, at_shift, *factor);
  factor.reset();
  finish(K, M, r);
  r.factor_seconds = factor_seconds;
  return r;
}

}  // namespace rigflex::linalg
