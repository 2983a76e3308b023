#pragma once
// The generalized symmetric eigenproblem of structural dynamics,
//   K x = lambda M x,   lambda = omega^2 in (rad/s)^2,
// with K symmetric positive semidefinite (free-free structures have rigid-body
// modes, lambda = 0) and M symmetric positive semidefinite and possibly
// singular (massless rotations: those give infinite eigenvalues, which are
// never returned).
//
// solve_lanczos: shift-invert Lanczos, Op = (K - sigma M)^-1 M in the M-inner
// product, with thick restart and full M-reorthogonalization on a cached
// CHOLMOD factorization. solve_dense: dense oracle for small models.
// Numerical outcomes (no convergence, singular pencil) are reported in the
// result; only invalid options throw (std::invalid_argument).
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "linalg/sparse_cholesky.hpp"

namespace rigflex::linalg {

struct EigenProgress {
  int restart = 0;           // thick restarts (and multiplicity checks) so far
  int converged = 0;         // wanted pairs converged, counted from the lowest
  int wanted = 0;            // EigenOptions::count
  long operator_applications = 0;
};

enum class EigenMethod {
  automatic,  // dense when n <= dense_threshold, Lanczos otherwise
  lanczos,
  dense,
};

struct EigenOptions {
  int count = 10;  // wanted lowest eigenpairs
  // sigma in (rad/s)^2; must lie below the lowest eigenvalue (K - sigma M
  // positive definite). Default: default_shift(K, M), slightly negative.
  std::optional<double> shift;
  // Convergence of Ritz pair i on the transformed problem:
  // |beta_m s_mi| <= tolerance * |theta_i|.
  double tolerance = 1e-10;
  int subspace = 0;  // Lanczos basis size, 0 = auto: max(2 count, count + 20, count + 2 block), capped at n
  int max_restarts = 200;
  unsigned seed = 1;   // deterministic start vectors
  // 1: single-vector Lanczos; > 1: block Lanczos, one multi-RHS solve per
  // block; 0: automatic, from the size of the factor and basis (automatic_block_size).
  int block_size = 0;
  // After convergence, restart once from a fresh random block orthogonal to
  // the converged vectors and confirm that no eigenvalue below the highest
  // wanted one was missed (Krylov methods can miss copies of a repeated
  // eigenvalue). Costs roughly the iterations needed to converge one more pair.
  // The block iteration skips it where every wanted eigenvalue came out with
  // fewer copies than the block has vectors (a block of b random vectors
  // spans up to b copies).
  bool verify_multiplicities = true;
  EigenMethod method = EigenMethod::automatic;
  Eigen::Index dense_threshold = 200;
  std::function<void(const EigenProgress&)> progress;  // optional
  // The factor of K - sigma M may hold at most this many bytes (0: no
  // limit); a larger one is refused after the symbolic analysis, before any
  // numeric work (EigenResult::over_memory_limit).
  double max_factor_bytes = 0;
  // Called after the analysis with the factor's predicted size and flops;
  // optional.
  std::function<void(const FactorStatistics&)> analyzed;
  // When the iteration stops at max_restarts, diagnose why (EigenResult::
  // stall) and, after a cluster or slow convergence, run once more on the
  // same factor with four times the basis (and a block as large as the
  // cluster, up to 8) from a fresh start. Never for a mechanism or a
  // near-singular shift (a fault of the problem that a basis does not cure),
  // never where the larger basis and the factor would exceed
  // max_factor_bytes. Every pair returned is checked as always;
  // EigenResult::retries and first_attempt say what happened.
  bool automatic_retry = true;

  // Throws std::invalid_argument naming the offending option.
  void validate(Eigen::Index n) const;
  // Block size actually used on a factor with factor_nnz nonzeros:
  // block_size, or automatic_block_size when it is 0. A given subspace must
  // leave room for two automatic blocks beyond the wanted pairs, else the
  // iteration stays single-vector: with less, thick restarts keep almost
  // the whole basis and the block iteration stalls.
  int resolved_block(Eigen::Index n, double factor_nnz) const;
  // Basis size actually used for a problem of size n and block size `block`
  // (from resolved_block).
  int resolved_subspace(Eigen::Index n, int block) const;
};

// Why a Lanczos run stopped short of `count` pairs, and what to change
// (diagnose_stall in lanczos_stall.hpp). Filled only when not converged.
enum class StallCause {
  none,
  clustered,            // the unconverged wanted pairs sit in a cluster of close eigenvalues
  near_singular_shift,  // the shift lies just below an eigenvalue: one direction swamps the rest
  mechanism,            // more near-zero eigenvalues than a free body's six rigid-body modes
  slow_convergence,     // none of the above: relative gaps too small for the basis and restarts given
};
struct EigenStall {
  StallCause cause = StallCause::none;
  std::string why;        // what the iteration saw, with frequencies in Hz
  std::string advice;     // what to change (EigenOptions fields; the CLI maps them to its options)
  double cluster_hz = 0;  // clustered: the frequency the cluster sits at
  int cluster_size = 0;   // clustered: Ritz values within the cluster width
};

struct EigenResult {
  bool converged = false;   // all `requested` pairs converged
  int requested = 0;
  int converged_count = 0;  // == eigenvalues.size()
  std::string message;
  Eigen::VectorXd eigenvalues;  // ascending lambda; only converged pairs
  Eigen::MatrixXd vectors;      // columns M-orthonormal: X' M X = I; largest |component| positive
  // Per pair: ||K x - lambda M x|| / max(||K x||, ||K||_1 ||x|| 1e-14).
  // The floor term keeps the ratio finite and scale-free for rigid-body
  // modes (lambda = 0), whose K x is pure rounding. Note the level that
  // rounding sets: forming K x alone errs by ~1e-16 ||K||_1 ||x||, so an
  // exact rigid-body mode reads ~1e-2 here, and a flexible mode at best
  // ~1e-16 lambda_max / lambda. Values <= 1 for rigid-body modes and
  // <= 1e-8 for the others indicate pairs correct to working precision.
  Eigen::VectorXd residuals;
  // Per pair: the normwise backward error of the generalized problem,
  // ||K x - lambda M x|| / ((||K||_1 + |lambda| ||M||_1) ||x||) (Higham &
  // Higham 1998): the smallest relative perturbation of K and M for which
  // the pair is exact. Scale-free and meaningful for rigid-body modes and for
  // ill-conditioned models alike, where the ratio above reaches only
  // eps ||K|| / ||K x||.
  Eigen::VectorXd backward_errors;
  double orthogonality_error = 0;  // max |X' M X - I|
  double shift = 0;
  int block_size = 0;  // the Lanczos block size used (0 for the dense path)
  int restarts = 0;
  long operator_applications = 0;  // applications of (K - sigma M)^-1 M to a vector
  double factor_seconds = 0, iteration_seconds = 0;
  std::vector<Eigen::Index> mechanism_dofs;  // filled when the shifted matrix was singular
  bool over_memory_limit = false;            // refused by EigenOptions::max_factor_bytes; message says why
  EigenStall stall;                          // when not converged: the cause and the remedy
  // Automatic retries (EigenOptions::automatic_retry) run; when a retry
  // converged, first_attempt holds why the first run stopped.
  int retries = 0;
  std::string first_attempt;

  // sqrt(max(lambda, 0)) / (2 pi): rigid-body modes whose lambda rounds to a
  // tiny negative value report 0 Hz.
  Eigen::VectorXd frequencies_hz() const;
};

// Default shift: sigma = -1e-10 * s, s = sum(K_ii) / sum(M_ii) over the DOFs
// with M_ii > 0 (the mass-weighted mean of the diagonal Rayleigh quotients,
// a scale of the upper spectrum that ignores massless DOFs and, unlike
// max(K_ii/M_ii), is not driven by one stiff, nearly massless DOF). Why so
// small: the convergence of the wanted modes depends on the gaps of
// 1/(lambda - sigma), which are undistorted only while |sigma| << lambda_1;
// the price, conditioning of K - sigma M ~ s/|sigma| along rigid-body modes,
// is harmless for shift-invert (errors fall along those very modes), as long
// as their pivots (~|sigma| times the rigid-body mass) stay well above
// rounding. factorize_pencil checks that and retries at 1000 sigma if not.
double default_shift(const SpMat& K, const SpMat& M);

// Automatic block size (EigenOptions::block_size = 0). A block of b vectors
// costs one b-column solve, which reads the factor L once for all b columns
// (a 4-column solve cost 1.8 single ones on a 100k-DOF plate), and its
// Gram-Schmidt reads the basis once for all b; but the block iteration needs
// more applications (1.3x on plates and ladders, 1.4x on a box girder,
// 1.7-1.9x on a 3D lattice, measured by bench/bench_block_size,
// docs/eigen-solver.md). Where the factor and the basis are too large for
// the caches, each pass over them is bound by memory bandwidth and reading
// them once per four columns wins; where they fit, the extra applications
// cost more. The rule reads the words one application streams, nnz(L) +
// n x basis (basis that of the single-vector iteration for `count` pairs),
// and takes 4 from kAutomaticBlockWords up. Deterministic: it depends on the
// factor's structure only, never on timings.
inline constexpr double kAutomaticBlockWords = 3e6;
inline constexpr int kAutomaticBlock = 4;
double application_words(Eigen::Index n, double factor_nnz, int count);
int automatic_block_size(Eigen::Index n, double factor_nnz, int count);

// Factorization of K - sigma M for the Lanczos, with the checks above.
struct PencilFactorization {
  bool ok = false;
  double shift = 0;
  std::string message;
  std::vector<Eigen::Index> mechanism_dofs;  // when K - sigma M is singular by a mechanism
  FactorStatus status;                       // of the last factorization tried
};
PencilFactorization factorize_pencil(const SpMat& K, const SpMat& M, std::optional<double> shift,
                                     SparseCholesky& factor);

// Lowest `options.count` eigenpairs by shift-invert Lanczos (or the dense
// path, see EigenOptions::method). Throws std::invalid_argument for invalid
// options or mismatched matrix sizes only.
EigenResult solve_lanczos(const SpMat& K, const SpMat& M, const EigenOptions& options);

// Same, reusing `factor_at_shift`, a successful factorization of
// K - sigma M (from factorize_pencil or SparseCholesky::factorize_shifted).
// sigma is factor_at_shift.shift() or, failing that, options.shift; one of
// them must be set and they must agree.
EigenResult solve_lanczos(const SpMat& K, const SpMat& M, const EigenOptions& options,
                          SparseCholesky& factor_at_shift);

// Dense oracle: Cholesky L L' = K - shift M, the standard symmetric problem
// L^-1 M L^-T y = nu y, lambda = shift + 1/nu, dropping nu ~ 0 (the infinite
// eigenvalues of a singular M). shift must lie below the lowest eigenvalue.
EigenResult solve_dense(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, double shift);

// A solver of K x = lambda M x under EigenOptions, where callers let the
// user choose one: empty means solve_lanczos; the MPI backend
// (linalg/slepc_eigen.hpp, slepc_backend) plugs in here.
using EigenBackend = std::function<EigenResult(const SpMat& K, const SpMat& M, const EigenOptions& options)>;

// Computes r.residuals and r.orthogonality_error from K, M and the pairs in
// r, independently of the solver that produced them.
void check_eigenpairs(const SpMat& K, const SpMat& M, EigenResult& r);

}  // namespace rigflex::linalg
