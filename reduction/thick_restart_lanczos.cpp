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
//
// Restarts keep the leading Ritz vectors; converged wanted ones are locked
// (moved to the front, couplings dropped), so that the matrix decomposed at
// each check holds only the active part. Once `count` pairs have converged,
// a multiplicity check continues from a fresh random block against the
// locked pairs: a single Krylov sequence sees one direction per distinct
// eigenvalue, and rounding alone does not reliably supply the other copies
// of a repeated one (a 7-fold eigenvalue came out with 4 copies without it).
#include "reduction/thick_restart_lanczos.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "reduction/random_block.hpp"

namespace rigflex::reduction::detail {
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

struct RitzPairs {
  VectorXd theta;             // descending
  MatrixXd vectors;           // eigenvectors of H[0:p, 0:p], same order
  VectorXd residual;          // ||H[p:p+r, 0:p] s_i||, the residual norm of Op y - theta y
  std::vector<char> locked;   // pair is one of the locked basis vectors
};

class ThickRestartLanczos {
 public:
  ThickRestartLanczos(const SpMat& M, SparseCholesky& factor, const LanczosSettings& settings)
      : M_(M),
        factor_(factor),
        s_(settings),
        random_(settings.seed),
        n_(M.rows()),
        stride_(std::max<Index>(1, settings.basis / (20 * settings.block))),
        Q_(MatrixXd::Zero(n_, s_.basis + s_.block)),
        MQ_(MatrixXd::Zero(n_, s_.basis + s_.block)),
        H_(MatrixXd::Zero(s_.basis + s_.block, s_.basis + s_.block)) {}

  LanczosOutcome run();

 private:
  enum class Check { pending, confirmed, refreshed };

  MatrixXd apply_to_mass_product(const MatrixXd& MV);
  MatrixXd random_range_block(Index cols);
  VectorXd mass_norms(const MatrixXd& W) const;
  MatrixXd project_out(MatrixXd& W, Index columns) const;
  Index append_block(const MatrixXd& W, Index start, const VectorXd& input_norms, MatrixXd& B);
  bool append_fresh_column(Index position);
  void start();
  void expand();
  void advance();
  RitzPairs ritz_pairs() const;
  bool converged(const RitzPairs& ritz, Index i) const;
  Index leading_converged(const RitzPairs& ritz) const;
  Index dominant_converged(const RitzPairs& ritz) const;
  void restart(const RitzPairs& ritz, Index keep);
  void thick_restart(const RitzPairs& ritz);
  void lock_and_refresh(const RitzPairs& ritz, Index keep);
  Check check_multiplicities(const RitzPairs& ritz);
  LanczosOutcome finish(const RitzPairs& ritz, Index pairs, bool converged, std::string message);
  void report(Index converged) const;

  const SpMat& M_;
  SparseCholesky& factor_;
  LanczosSettings s_;
  RandomBlocks random_;
  Index n_;
  // Convergence is tested every `stride_` expansions (an eigendecomposition
  // of H costs O(m^3)), and always before a restart.
  Index stride_;
  MatrixXd Q_, MQ_, H_;
  Index locked_ = 0;  // Q[:, 0:locked]: converged Ritz vectors, H diagonal and uncoupled there
  Index p_ = 0;       // basis columns whose image under Op is represented in H
  Index r_ = 0;       // residual block Q[:, p:p+r]; 0 when the Krylov space is exhausted
  long applications_ = 0;
  int restarts_ = 0;  // thick restarts and multiplicity-check rounds
  bool verifying_ = false;
  double theta_reference_ = 0.0;  // lowest wanted theta when the current check round began
};

MatrixXd ThickRestartLanczos::apply_to_mass_product(const MatrixXd& MV) {
  applications_ += MV.cols();
  return factor_.solve(MV);
}

MatrixXd ThickRestartLanczos::random_range_block(Index cols) {
  return apply_to_mass_product(M_ * random_.next(n_, cols));
}

VectorXd ThickRestartLanczos::mass_norms(const MatrixXd& W) const {
  const MatrixXd MW = M_ * W;
  VectorXd norms(W.cols());
  for (Index c = 0; c < W.cols(); ++c) norms[c] = std::sqrt(std::max(0.0, W.col(c).dot(MW.col(c))));
  return norms;
}

// Classical Gram-Schmidt twice against Q[:, 0:columns]; returns the total
// coefficients (columns x W.cols()).
MatrixXd ThickRestartLanczos::project_out(MatrixXd& W, Index columns) const {
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
Index ThickRestartLanczos::append_block(const MatrixXd& W, Index start, const VectorXd& input_norms,
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

bool ThickRestartLanczos::append_fresh_column(Index position) {
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

void ThickRestartLanczos::start() {
  const MatrixXd W = random_range_block(s_.block);
  MatrixXd B;
  p_ = 0;
  r_ = append_block(W, 0, mass_norms(W), B);
}

// One block Lanczos step: Op applied to the residual block, which joins the
// represented basis; the orthogonalized result becomes the new residual block.
void ThickRestartLanczos::expand() {
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
RitzPairs ThickRestartLanczos::ritz_pairs() const {
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

bool ThickRestartLanczos::converged(const RitzPairs& ritz, Index i) const {
  return ritz.residual[i] <= s_.tolerance * std::abs(ritz.theta[i]);
}

Index ThickRestartLanczos::leading_converged(const RitzPairs& ritz) const {
  const Index wanted = std::min<Index>(s_.count, ritz.theta.size());
  Index k = 0;
  while (k < wanted && converged(ritz, k)) ++k;
  return k;
}

// Number of leading pairs that are converged and dominate the lowest wanted
// theta beyond what rounding allows (see kRoundingShare); 0 if all of those
// are locked already.
Index ThickRestartLanczos::dominant_converged(const RitzPairs& ritz) const {
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
void ThickRestartLanczos::restart(const RitzPairs& ritz, Index keep) {
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

void ThickRestartLanczos::thick_restart(const RitzPairs& ritz) {
  // Keep the wanted pairs and half of the rest of the basis (Wu & Simon keep
  // a similar share): the unconverged Ritz vectors next to the wanted ones
  // carry most of the progress made so far.
  restart(ritz, std::min(s_.count + (s_.basis - s_.count) / 2, s_.basis - s_.block));
}

// Locks the `keep` leading pairs (all converged) and continues from a fresh
// random block orthogonal to them.
void ThickRestartLanczos::lock_and_refresh(const RitzPairs& ritz, Index keep) {
  restart(ritz, keep);
  MatrixXd W = random_range_block(s_.block);
  const VectorXd norms = mass_norms(W);
  project_out(W, p_);
  MatrixXd B;
  r_ = append_block(W, p_, norms, B);
  H_.block(p_, 0, H_.rows() - p_, p_).setZero();
  H_.block(0, p_, p_, H_.cols() - p_).setZero();
}

LanczosOutcome ThickRestartLanczos::finish(const RitzPairs& ritz, Index pairs, bool converged,
                                           std::string message) {
  // Purification: x = Op y / theta, with Op y = C^-1 (M Q s) from MQ.
  const MatrixXd MY = MQ_.leftCols(p_) * ritz.vectors.leftCols(pairs);
  LanczosOutcome out;
  out.X = apply_to_mass_product(MY);
  for (Index i = 0; i < pairs; ++i) out.X.col(i) /= ritz.theta[i];
  out.restarts = restarts_;
  out.converged = converged;
  out.message = std::move(message);
  out.applications = applications_;
  report(pairs);
  return out;
}

void ThickRestartLanczos::report(Index converged) const {
  if (s_.progress == nullptr || !*s_.progress) return;
  EigenProgress progress;
  progress.restart = restarts_;
  progress.converged = static_cast<int>(converged);
  progress.wanted = static_cast<int>(s_.count);
  progress.operator_applications = applications_;
  (*s_.progress)(progress);
}

// Expands the basis until a convergence check is due or no room is left.
void ThickRestartLanczos::advance() {
  Index steps = 0;
  while (r_ > 0 && p_ + r_ <= s_.basis) {
    expand();
    ++steps;
    if (p_ >= s_.count && steps % stride_ == 0) return;
  }
}

// The multiplicity check: after convergence, lock the wanted pairs and run
// on from a fresh random block. A copy of a repeated eigenvalue that the
// Krylov space missed (a single start vector spans one direction per
// distinct eigenvalue) shows up as a new Ritz value above the lowest wanted
// one; the round ends once the best new Ritz value is resolved.
ThickRestartLanczos::Check ThickRestartLanczos::check_multiplicities(const RitzPairs& ritz) {
  const Index c = s_.count;
  if (verifying_) {
    if (p_ <= c) return Check::pending;
    const double gap = ritz.theta[c - 1] - ritz.theta[c];
    const double bound = std::max(s_.tolerance * ritz.theta[c], kResolvedGapFraction * gap);
    if (ritz.residual[c] > bound) return Check::pending;
    if (ritz.theta[c - 1] <= theta_reference_ * (1.0 + kMissedEigenvalueGrowth)) {
      return Check::confirmed;
    }
  }
  // First round, or a missed eigenvalue entered the wanted set: check again.
  verifying_ = true;
  theta_reference_ = ritz.theta[c - 1];
  lock_and_refresh(ritz, c);
  ++restarts_;
  return Check::refreshed;
}

LanczosOutcome ThickRestartLanczos::run() {
  start();
  while (true) {
    advance();
    const RitzPairs ritz = ritz_pairs();
    if (r_ == 0) {  // Krylov space exhausted: every Ritz pair is exact
      const Index pairs = std::min<Index>(s_.count, p_);
      return finish(ritz, pairs, pairs == s_.count,
                    pairs == s_.count ? "converged"
                                      : "only " + std::to_string(pairs) +
                                            " finite eigenvalues (M is singular)");
    }
    if (const Index dominant = dominant_converged(ritz); dominant > 0) {
      lock_and_refresh(ritz, dominant);
      continue;
    }
    const Index leading = leading_converged(ritz);
    if (leading >= s_.count) {
      if (!s_.verify) return finish(ritz, s_.count, true, "converged");
      const Check check = check_multiplicities(ritz);
      if (check == Check::confirmed) return finish(ritz, s_.count, true, "converged");
      if (check == Check::refreshed) continue;
    }
    if (p_ + r_ > s_.basis) {
      if (restarts_ >= s_.max_restarts) {
        if (leading >= s_.count) {
          return finish(ritz, s_.count, true,
                        "converged (the check for missed repeated eigenvalues was cut short "
                        "by max_restarts)");
        }
        return finish(ritz, leading, false,
                      "not converged after " + std::to_string(restarts_) + " restarts (" +
                          std::to_string(leading) + " of " + std::to_string(s_.count) +
                          " pairs converged)");
      }
      thick_restart(ritz);
      ++restarts_;
      report(leading);
    }
  }
}

}  // namespace

LanczosOutcome thick_restart_lanczos(const SpMat& M, SparseCholesky& factor,
                                     const LanczosSettings& settings) {
  return ThickRestartLanczos(M, factor, settings).run();
}

}  // namespace rigflex::reduction::detail
