// Shift-invert thick-restart Lanczos (Wu & Simon 2000; block form in the
// Krylov-Schur style of Stewart 2001) for K x = lambda M x.
//
// Operator: Op = C^-1 M, C = K - sigma M (positive definite), self-adjoint in
// the M-inner product; its eigenvalues nu = 1 / (lambda - sigma) are largest
// for the lowest lambda. With M singular the M-inner product is only a
// semi-inner product, but it is a true one on range(Op): every start vector
// is Op(random), every basis vector stays in range(Op) up to rounding, and
// the final Ritz vectors are purified, x = Op y / theta (Ericsson &
// Nour-Omid), which removes any null(M) component (Op kills it).
//
// Basis: Q (n x (m + b)) M-orthonormal, MQ = M Q kept alongside so that
// every M-inner product is a dense product. Relation maintained:
//   Op Q[:, 0:p] = Q[:, 0:p] H[0:p, 0:p] + Q[:, p:p+r] H[p:p+r, 0:p],
// H symmetric: block tridiagonal after expansions, arrowhead after a thick
// restart. Every new block is M-orthogonalized against the whole basis by
// classical Gram-Schmidt twice (DGKS), a third time after heavy cancellation.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "reduction/eigen_postprocess.hpp"
#include "reduction/eigen_solver.hpp"
#include "reduction/random_block.hpp"

namespace rigflex::reduction {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// Gram-Schmidt: a third pass when the norm fell below this fraction of the
// norm before projection (orthogonality after CGS2 degrades like
// eps * ||w|| / ||w_orth||).
constexpr double kExtraPassRatio = 1e-3;
// A new direction whose norm fell below this fraction is linearly dependent
// (an invariant subspace): the basis continues with a fresh random direction.
constexpr double kDeflationRatio = 1e-12;
// A fresh random direction orthogonal to the basis that keeps less than this
// fraction of its norm means the basis spans range(Op): nothing is left.
constexpr double kExhaustionRatio = 1e-8;
// In the multiplicity check, a wanted theta that grew by more than this
// relative amount means a missed eigenvalue was found.
constexpr double kMissedEigenvalueGrowth = 1e-8;
// In the multiplicity check, the best new Ritz value is resolved when its
// residual is below this fraction of its distance to the lowest wanted one.
constexpr double kResolvedGapFraction = 0.1;
// Rounding in a Lanczos step is ~eps * ||Op v||, and so is the accuracy of
// the eigendecomposition of H, ~eps * ||H||. While pairs with a theta far
// above the lowest wanted one are active (rigid-body modes at a tiny shift:
// ratios of 1e9), these absolute errors exceed tol * theta_count. Such pairs
// converge in a step or two; they are then locked (couplings dropped, out
// of the decomposed matrix) and the rest of the basis, written while they
// dominated, restarts from a fresh block. The threshold keeps those errors
// at kRoundingShare of the tolerance.
constexpr double kRoundingShare = 1e-3;

struct LanczosSettings {
  Index count = 0;
  Index basis = 0;  // m
  Index block = 1;  // b
  double tolerance = 0;
  int max_restarts = 0;
  bool verify = true;
  unsigned seed = 1;
  const std::function<void(const EigenProgress&)>* progress = nullptr;
};

struct RitzPairs {
  VectorXd theta;             // descending
  MatrixXd vectors;           // eigenvectors of H[0:p, 0:p], same order
  VectorXd residual;          // ||H[p:p+r, 0:p] s_i||, the residual norm of Op y - theta y
  std::vector<char> locked;   // pair is one of the locked basis vectors
};

struct LanczosOutcome {
  MatrixXd X;  // purified Ritz vectors of the leading converged pairs
  int restarts = 0;
  bool converged = false;
  std::string message;
};

class ShiftInvertLanczos {
 public:
  ShiftInvertLanczos(const SpMat& M, SparseCholesky& factor, const LanczosSettings& settings)
      : M_(M),
        factor_(factor),
        s_(settings),
        random_(settings.seed),
        n_(M.rows()),
        Q_(MatrixXd::Zero(n_, s_.basis + s_.block)),
        MQ_(MatrixXd::Zero(n_, s_.basis + s_.block)),
        H_(MatrixXd::Zero(s_.basis + s_.block, s_.basis + s_.block)) {}

  LanczosOutcome run();
  long applications() const { return applications_; }

 private:
  MatrixXd apply_to_mass_product(const MatrixXd& MV);
  MatrixXd random_range_block(Index cols);
  VectorXd mass_norms(const MatrixXd& W) const;
  MatrixXd project_out(MatrixXd& W, Index columns) const;
  Index append_block(const MatrixXd& W, Index start, const VectorXd& input_norms, MatrixXd& B);
  bool append_fresh_column(Index position);
  void start();
  void expand();
  RitzPairs ritz_pairs() const;
  bool converged(const RitzPairs& ritz, Index i) const;
  Index leading_converged(const RitzPairs& ritz) const;
  Index dominant_converged(const RitzPairs& ritz) const;
  void restart(const RitzPairs& ritz, Index keep);
  void thick_restart(const RitzPairs& ritz);
  void lock_and_refresh(const RitzPairs& ritz, Index keep);
  LanczosOutcome finish(const RitzPairs& ritz, Index pairs, int restarts, bool converged,
                        std::string message);
  void report(int restarts, Index converged) const;

  const SpMat& M_;
  SparseCholesky& factor_;
  LanczosSettings s_;
  RandomBlocks random_;
  Index n_;
  MatrixXd Q_, MQ_, H_;
  Index locked_ = 0;  // Q[:, 0:locked]: converged Ritz vectors, H diagonal and uncoupled there
  Index p_ = 0;       // basis columns whose image under Op is represented in H
  Index r_ = 0;       // residual block Q[:, p:p+r]; 0 when the Krylov space is exhausted
  long applications_ = 0;
};

MatrixXd ShiftInvertLanczos::apply_to_mass_product(const MatrixXd& MV) {
  applications_ += MV.cols();
  return factor_.solve(MV);
}

MatrixXd ShiftInvertLanczos::random_range_block(Index cols) {
  return apply_to_mass_product(M_ * random_.next(n_, cols));
}

VectorXd ShiftInvertLanczos::mass_norms(const MatrixXd& W) const {
  const MatrixXd MW = M_ * W;
  VectorXd norms(W.cols());
  for (Index c = 0; c < W.cols(); ++c) norms[c] = std::sqrt(std::max(0.0, W.col(c).dot(MW.col(c))));
  return norms;
}

// Classical Gram-Schmidt twice against Q[:, 0:columns]; returns the total
// coefficients (columns x W.cols()).
MatrixXd ShiftInvertLanczos::project_out(MatrixXd& W, Index columns) const {
  MatrixXd C = MQ_.leftCols(columns).transpose() * W;
  W.noalias() -= Q_.leftCols(columns) * C;
  const MatrixXd C2 = MQ_.leftCols(columns).transpose() * W;
  W.noalias() -= Q_.leftCols(columns) * C2;
  C += C2;
  return C;
}

// Appends the M-orthonormalized columns of W (already orthogonal to
// Q[:, 0:start]) at Q[:, start:...]: W = Q[:, start:start+k] B with B upper
// triangular (k x W.cols()). A dependent column is replaced by a fresh random
// direction coupled to nothing (B row zero there). Returns k, smaller than
// W.cols() only when the basis spans all of range(Op).
Index ShiftInvertLanczos::append_block(const MatrixXd& W, Index start, const VectorXd& input_norms,
                                       MatrixXd& B) {
  B = MatrixXd::Zero(W.cols(), W.cols());
  Index appended = 0;
  bool exhausted = false;
  for (Index c = 0; c < W.cols(); ++c) {
    VectorXd w = W.col(c);
    for (int pass = 0; pass < 2 && appended > 0; ++pass) {
      const VectorXd g = MQ_.middleCols(start, appended).transpose() * w;
      w.noalias() -= Q_.middleCols(start, appended) * g;
      B.col(c).head(appended) += g;
    }
    if (exhausted) continue;  // only its coefficients are still needed
    const Index position = start + appended;
    VectorXd Mw = M_ * w;
    double beta = std::sqrt(std::max(0.0, w.dot(Mw)));
    if (beta < kExtraPassRatio * input_norms[c]) {
      const VectorXd g = MQ_.leftCols(position).transpose() * w;
      w.noalias() -= Q_.leftCols(position) * g;
      B.col(c).head(appended) += g.tail(appended);
      Mw = M_ * w;
      beta = std::sqrt(std::max(0.0, w.dot(Mw)));
    }
    if (beta <= kDeflationRatio * input_norms[c]) {
      exhausted = !append_fresh_column(position);
      if (!exhausted) ++appended;
      continue;
    }
    Q_.col(position) = w / beta;
    MQ_.col(position) = Mw / beta;
    B(appended, c) = beta;
    ++appended;
  }
  B.conservativeResize(appended, W.cols());
  return appended;
}

bool ShiftInvertLanczos::append_fresh_column(Index position) {
  VectorXd w = random_range_block(1).col(0);
  const double initial = mass_norms(w)[0];
  // Three passes: the random vector may lie mostly in the basis already.
  for (int pass = 0; pass < 3; ++pass) {
    const VectorXd g = MQ_.leftCols(position).transpose() * w;
    w.noalias() -= Q_.leftCols(position) * g;
  }
  const VectorXd Mw = M_ * w;
  const double beta = std::sqrt(std::max(0.0, w.dot(Mw)));
  if (!(beta > kExhaustionRatio * initial)) return false;
  Q_.col(position) = w / beta;
  MQ_.col(position) = Mw / beta;
  return true;
}

void ShiftInvertLanczos::start() {
  const MatrixXd W = random_range_block(s_.block);
  MatrixXd B;
  p_ = 0;
  r_ = append_block(W, 0, mass_norms(W), B);
}

// One block Lanczos step: Op applied to the residual block, which joins the
// represented basis; the orthogonalized result becomes the new residual block.
void ShiftInvertLanczos::expand() {
  const Index j = p_ + r_;
  MatrixXd W = apply_to_mass_product(MQ_.middleCols(p_, r_));
  const VectorXd norms = mass_norms(W);
  const MatrixXd C = project_out(W, j);
  const MatrixXd D = C.bottomRows(r_);
  H_.block(p_, p_, r_, r_) = 0.5 * (D + D.transpose());
  MatrixXd B;
  const Index appended = append_block(W, j, norms, B);
  H_.block(j, p_, appended, r_) = B;
  H_.block(p_, j, r_, appended) = B.transpose();
  p_ = j;
  r_ = appended;
}

// Ritz pairs of H[0:p, 0:p]: the locked pairs as they are, the active block
// H[locked:p, locked:p] decomposed; all sorted by descending theta.
RitzPairs ShiftInvertLanczos::ritz_pairs() const {
  RitzPairs ritz;
  const Index active = p_ - locked_;
  VectorXd theta(p_), residual = VectorXd::Zero(p_);
  MatrixXd vectors = MatrixXd::Zero(p_, p_);
  theta.head(locked_) = H_.diagonal().head(locked_);
  vectors.topLeftCorner(locked_, locked_).setIdentity();
  if (active > 0) {
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(H_.block(locked_, locked_, active, active));
    theta.tail(active) = eig.eigenvalues();
    vectors.bottomRightCorner(active, active) = eig.eigenvectors();
    if (r_ > 0) {
      residual.tail(active) =
          (H_.block(p_, locked_, r_, active) * eig.eigenvectors()).colwise().norm().transpose();
    }
  }
  std::vector<Index> order(static_cast<size_t>(p_));
  for (Index i = 0; i < p_; ++i) order[static_cast<size_t>(i)] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](Index a, Index b) { return theta[a] > theta[b]; });
  ritz.theta.resize(p_);
  ritz.residual.resize(p_);
  ritz.vectors.resize(p_, p_);
  ritz.locked.resize(static_cast<size_t>(p_));
  for (Index i = 0; i < p_; ++i) {
    const Index from = order[static_cast<size_t>(i)];
    ritz.theta[i] = theta[from];
    ritz.residual[i] = residual[from];
    ritz.vectors.col(i) = vectors.col(from);
    ritz.locked[static_cast<size_t>(i)] = from < locked_;
  }
  return ritz;
}

bool ShiftInvertLanczos::converged(const RitzPairs& ritz, Index i) const {
  return ritz.residual[i] <= s_.tolerance * std::abs(ritz.theta[i]);
}

Index ShiftInvertLanczos::leading_converged(const RitzPairs& ritz) const {
  const Index wanted = std::min<Index>(s_.count, ritz.theta.size());
  Index k = 0;
  while (k < wanted && converged(ritz, k)) ++k;
  return k;
}

// Number of leading pairs that are converged and dominate the lowest wanted
// theta beyond what rounding allows (see kRoundingShare); 0 if all of those
// are locked already.
Index ShiftInvertLanczos::dominant_converged(const RitzPairs& ritz) const {
  const Index wanted = std::min<Index>(s_.count, ritz.theta.size());
  if (wanted == 0) return 0;
  const double limit = kRoundingShare * s_.tolerance / std::numeric_limits<double>::epsilon() *
                       ritz.theta[wanted - 1];
  Index k = 0;
  bool unlocked = false;
  while (k < wanted && converged(ritz, k) && ritz.theta[k] > limit) {
    unlocked = unlocked || !ritz.locked[static_cast<size_t>(k)];
    ++k;
  }
  return unlocked ? k : 0;
}

// Rotates the basis onto the leading `keep` Ritz vectors, locking the
// converged wanted ones (first in the basis, H diagonal and uncoupled
// there) and keeping the others with their arrowhead coupling to the
// residual block, which moves down to follow them.
void ShiftInvertLanczos::restart(const RitzPairs& ritz, Index keep) {
  auto lockable = [&](Index i) { return i < s_.count && converged(ritz, i); };
  std::vector<Index> order;
  for (Index i = 0; i < keep; ++i) {
    if (lockable(i)) order.push_back(i);
  }
  const auto newly_locked = static_cast<Index>(order.size());
  for (Index i = 0; i < keep; ++i) {
    if (!lockable(i)) order.push_back(i);
  }
  const MatrixXd S = ritz.vectors(Eigen::all, order);
  MatrixXd coupling = H_.block(p_, 0, r_, p_) * S;
  coupling.leftCols(newly_locked).setZero();
  const VectorXd theta = ritz.theta(order);
  const Index old_p = p_;
  Q_.leftCols(keep) = (Q_.leftCols(old_p) * S).eval();
  MQ_.leftCols(keep) = (MQ_.leftCols(old_p) * S).eval();
  Q_.middleCols(keep, r_) = Q_.middleCols(old_p, r_).eval();
  MQ_.middleCols(keep, r_) = MQ_.middleCols(old_p, r_).eval();
  H_.setZero();
  H_.diagonal().head(keep) = theta;
  H_.block(keep, 0, r_, keep) = coupling;
  H_.block(0, keep, keep, r_) = coupling.transpose();
  locked_ = newly_locked;
  p_ = keep;
}

void ShiftInvertLanczos::thick_restart(const RitzPairs& ritz) {
  // Keep the wanted pairs and half of the rest of the basis (Wu & Simon keep
  // a similar share): the unconverged Ritz vectors next to the wanted ones
  // carry most of the progress made so far.
  restart(ritz, std::min(s_.count + (s_.basis - s_.count) / 2, s_.basis - s_.block));
}

// Locks the `keep` leading pairs (all converged) and continues from a fresh
// random block orthogonal to them.
void ShiftInvertLanczos::lock_and_refresh(const RitzPairs& ritz, Index keep) {
  restart(ritz, keep);
  MatrixXd W = random_range_block(s_.block);
  const VectorXd norms = mass_norms(W);
  project_out(W, p_);
  MatrixXd B;
  r_ = append_block(W, p_, norms, B);
  H_.block(p_, 0, H_.rows() - p_, p_).setZero();
  H_.block(0, p_, p_, H_.cols() - p_).setZero();
}

LanczosOutcome ShiftInvertLanczos::finish(const RitzPairs& ritz, Index pairs, int restarts,
                                          bool converged, std::string message) {
  // Purification: x = Op y / theta, with Op y = C^-1 (M Q s) from MQ.
  const MatrixXd MY = MQ_.leftCols(p_) * ritz.vectors.leftCols(pairs);
  LanczosOutcome out;
  out.X = apply_to_mass_product(MY);
#ifdef LANCZOS_DEBUG
  {
    MatrixXd OQ = factor_.solve(MatrixXd(MQ_.leftCols(p_)));
    MatrixXd E = OQ - Q_.leftCols(p_) * H_.topLeftCorner(p_, p_) - Q_.middleCols(p_, r_) * H_.block(p_, 0, r_, p_);
    MatrixXd Yr = Q_.leftCols(locked_);
    MatrixXd Ef = E - Yr * (MQ_.leftCols(locked_).transpose() * E);
    for (Index j = 0; j < p_; ++j) fprintf(stderr, "col %ld relerr %.2e flexerr %.2e Hjj %.3e\n", (long)j, E.col(j).norm(), Ef.col(j).norm(), H_(j,j));
    const MatrixXd Y = Q_.leftCols(p_) * ritz.vectors.leftCols(pairs);
    for (Index i = 0; i < pairs; ++i) {
      VectorXd res = out.X.col(i) - ritz.theta[i] * Y.col(i);
      res -= Yr * (MQ_.leftCols(locked_).transpose() * res);
      VectorXd Mres = M_ * res;
      fprintf(stderr, "pair %ld theta %.6e est %.3e true(flex) %.3e locked %d\n", (long)i, ritz.theta[i], ritz.residual[i], std::sqrt(res.dot(Mres)), (int)ritz.locked[i]);
    }
    fprintf(stderr, "locked %ld\n", (long)locked_);
  }
#endif

  for (Index i = 0; i < pairs; ++i) out.X.col(i) /= ritz.theta[i];
  out.restarts = restarts;
  out.converged = converged;
  out.message = std::move(message);
  report(restarts, pairs);
  return out;
}

void ShiftInvertLanczos::report(int restarts, Index converged) const {
  if (s_.progress == nullptr || !*s_.progress) return;
  EigenProgress progress;
  progress.restart = restarts;
  progress.converged = static_cast<int>(converged);
  progress.wanted = static_cast<int>(s_.count);
  progress.operator_applications = applications_;
  (*s_.progress)(progress);
}

LanczosOutcome ShiftInvertLanczos::run() {
  start();
  int restarts = 0;
  bool verifying = false;
  double theta_reference = 0.0;
  // Convergence is tested every `stride` expansions (an eigendecomposition
  // of H costs O(m^3)), and always before a restart.
  const Index stride = std::max<Index>(1, s_.basis / (20 * s_.block));
  Index steps = 0;
  while (true) {
    const bool room = r_ > 0 && p_ + r_ <= s_.basis;
    if (room) {
      expand();
      ++steps;
      const bool can_continue = r_ > 0 && p_ + r_ <= s_.basis;
      if (can_continue && (p_ < s_.count || steps % stride != 0)) continue;
    }
    const RitzPairs ritz = ritz_pairs();
    if (r_ == 0) {  // Krylov space exhausted: every Ritz pair is exact
      const Index pairs = std::min<Index>(s_.count, p_);
      return finish(ritz, pairs, restarts, pairs == s_.count,
                    pairs == s_.count ? "converged"
                                      : "only " + std::to_string(pairs) +
                                            " finite eigenvalues (M is singular)");
    }
    const Index leading = leading_converged(ritz);
    if (const Index dominant = dominant_converged(ritz); dominant > 0) {
      lock_and_refresh(ritz, dominant);
      continue;
    }
    if (leading >= s_.count) {
      if (!s_.verify) return finish(ritz, s_.count, restarts, true, "converged");
      if (!verifying) {
        verifying = true;
        theta_reference = ritz.theta[s_.count - 1];
        lock_and_refresh(ritz, s_.count);
        ++restarts;
        continue;
      }
      if (p_ > s_.count) {
        const double gap = ritz.theta[s_.count - 1] - ritz.theta[s_.count];
        const double bound = std::max(s_.tolerance * ritz.theta[s_.count],
                                      kResolvedGapFraction * gap);
        if (ritz.residual[s_.count] <= bound) {
          if (ritz.theta[s_.count - 1] <= theta_reference * (1.0 + kMissedEigenvalueGrowth)) {
            return finish(ritz, s_.count, restarts, true, "converged");
          }
          // A missed eigenvalue entered the wanted set: check again.
          theta_reference = ritz.theta[s_.count - 1];
          lock_and_refresh(ritz, s_.count);
          ++restarts;
          continue;
        }
      }
    }
    if (p_ + r_ > s_.basis) {
      if (restarts >= s_.max_restarts) {
        return finish(ritz, leading, restarts, false,
                      "not converged after " + std::to_string(restarts) + " restarts (" +
                          std::to_string(leading) + " of " + std::to_string(s_.count) +
                          " pairs converged)");
      }
      thick_restart(ritz);
      ++restarts;
      report(restarts, leading);
    }
  }
}

LanczosSettings settings_from(const EigenOptions& options, Index n) {
  LanczosSettings s;
  s.count = options.count;
  s.block = options.block_size;
  s.basis = options.resolved_subspace(n);
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

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool use_dense(const EigenOptions& options, Index n) {
  return options.method == EigenMethod::dense ||
         (options.method == EigenMethod::automatic && n <= options.dense_threshold);
}

}  // namespace

EigenResult solve_lanczos(const SpMat& K, const SpMat& M, const EigenOptions& options,
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
  ShiftInvertLanczos lanczos(M, factor_at_shift, settings_from(options, K.rows()));
  LanczosOutcome outcome = lanczos.run();
  r.eigenvalues = rayleigh_ritz(K, M, outcome.X);
  normalize_signs(outcome.X);
  r.vectors = std::move(outcome.X);
  r.converged_count = static_cast<int>(r.eigenvalues.size());
  r.converged = outcome.converged;
  r.message = std::move(outcome.message);
  r.restarts = outcome.restarts;
  r.operator_applications = lanczos.applications();
  r.iteration_seconds = seconds_since(start);
  check_eigenpairs(K, M, r);
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
  SparseCholesky factor;
  const PencilFactorization pencil = factorize_pencil(K, M, options.shift, factor);
  const double factor_seconds = seconds_since(start);
  if (!pencil.ok) {
    EigenResult r;
    r.requested = options.count;
    r.shift = pencil.shift;
    r.message = pencil.message;
    r.mechanism_dofs = pencil.mechanism_dofs;
    r.factor_seconds = factor_seconds;
    return r;
  }
  EigenOptions at_shift = options;
  at_shift.shift = pencil.shift;
  EigenResult r = solve_lanczos(K, M, at_shift, factor);
  r.factor_seconds = factor_seconds;
  return r;
}

}  // namespace rigflex::reduction
