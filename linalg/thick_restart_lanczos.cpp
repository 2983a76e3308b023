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
// Basis: Q (n x (m + b)) M-orthonormal. It is, with the factor, most of the
// memory the iteration holds: M times the basis is not kept (Q' M w is
// computed as Q' (M w), a sparse product per Gram-Schmidt pass), only M
// times the residual block, the next input of the solve. Relation
// maintained:
//   Op Q[:, 0:p] = Q[:, 0:p] H[0:p, 0:p] + Q[:, p:p+r] H[p:p+r, 0:p],
// H symmetric: block tridiagonal after expansions, arrowhead after a thick
// restart. Every new block is M-orthogonalized against the whole basis by
// classical Gram-Schmidt, repeated while a pass cancels more than the DGKS
// criterion allows (Daniel, Gragg, Kaufman & Stewart 1976; ARPACK's test),
// at most three passes.
//
// Restarts keep the leading Ritz vectors; converged wanted ones are locked
// (moved to the front, couplings dropped), so that the matrix decomposed at
// each check holds only the active part. Once `count` pairs have converged,
// a multiplicity check continues from a fresh random block against the
// locked pairs: a single Krylov sequence sees one direction per distinct
// eigenvalue, and rounding alone does not reliably supply the other copies
// of a repeated one (a 7-fold eigenvalue came out with 4 copies without it).
// A block of b random vectors does supply up to b copies: where every wanted
// eigenvalue has fewer than b converged copies, the check is skipped.
#include "linalg/thick_restart_lanczos.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "linalg/block_kernels.hpp"
#include "linalg/random_block.hpp"

namespace rigflex::linalg::detail {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// Gram-Schmidt against the basis is repeated while a pass leaves less than
// this fraction of the norm it started from (the DGKS criterion with
// ARPACK's constant, 1/sqrt(2)): below it, the rounding of the pass may have
// left components along the basis above eps.
constexpr double kRepeatPassRatio = 0.717;
constexpr int kMaxPasses = 3;
// Within a new block: a pass against the whole basis when the norm fell
// below this fraction of the norm before projection.
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
// Converged Ritz values this close (relative) count as copies of one
// eigenvalue when deciding whether the block saw all of them (see
// block_saw_every_copy). Copies converge to ~tolerance of each other; the
// width is far wider, so that a nearly repeated eigenvalue, whose copies a
// Krylov space separates only slowly, is treated as repeated: the safe side.
constexpr double kCopyWidth = 1e-6;
// Rounding in a Lanczos step is ~eps * ||Op v||, and so is the accuracy of
// the eigendecomposition of H, ~eps * ||H||. While pairs with a theta far
// above the lowest wanted one are active (rigid-body modes at a tiny shift:
// ratios of 1e9), these absolute errors exceed tol * theta_count. Such pairs
// converge in a step or two; they are then locked (couplings dropped, out
// of the decomposed matrix) and the rest of the basis, written while they
// dominated, restarts from a fresh block. The threshold keeps those errors
// at kRoundingShare of the tolerance.
constexpr double kRoundingShare = 1e-3;
// Rows per slice when the basis is rotated in place: the product of a slice
// with the rotation needs a temporary of this many rows only.
constexpr Index kRotationRows = 2048;

struct RitzPairs {
  VectorXd theta;             // descending
  MatrixXd vectors;           // eigenvectors of H[0:p, 0:p], same order
  VectorXd residual;          // ||H[p:p+r, 0:p] s_i||, the residual norm of Op y - theta y
  std::vector<char> locked;   // pair is one of the locked basis vectors
};

// sqrt(w' M w) per column, from W and M W.
VectorXd mass_norms(const Eigen::Ref<const MatrixXd>& W, const Eigen::Ref<const MatrixXd>& MW) {
  VectorXd norms(W.cols());
  for (Index c = 0; c < W.cols(); ++c) {
    norms[c] = std::sqrt(std::max(0.0, W.col(c).dot(MW.col(c))));
  }
  return norms;
}

class ThickRestartLanczos {
 public:
  ThickRestartLanczos(const SpMat& M, SparseCholesky& factor, const LanczosSettings& settings)
      : M_(M),
        factor_(factor),
        s_(settings),
        random_(settings.seed),
        n_(M.rows()),
        stride_(std::max<Index>(1, settings.basis / (20 * settings.block))),
        Q_(n_, s_.basis + s_.block),
        MR_(n_, s_.block),
        MW_(n_, s_.block),
        H_(MatrixXd::Zero(s_.basis + s_.block, s_.basis + s_.block)) {}

  LanczosOutcome run();

 private:
  enum class Check { pending, confirmed, refreshed };

  void apply_to_mass_product(Eigen::Ref<MatrixXd> MV);
  MatrixXd random_range_block(Index cols);
  void mass(const Eigen::Ref<const MatrixXd>& W, Eigen::Ref<MatrixXd> MW) const;
  MatrixXd orthogonalize(Eigen::Ref<MatrixXd> W, Eigen::Ref<MatrixXd> MW, Index columns) const;
  Index append_block(Eigen::Ref<MatrixXd> W, Eigen::Ref<MatrixXd> MW, Index start,
                     const VectorXd& input_norms, MatrixXd& B);
  bool append_fresh_column(Index position, Index block_column);
  void append_random_block();
  void rotate(const MatrixXd& S);
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
  bool block_saw_every_copy(const RitzPairs& ritz) const;
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
  MatrixXd Q_;   // basis, then the residual block
  MatrixXd MR_;  // M Q[:, p:p+r]: the residual block's M-image, input of the next solve
  MatrixXd MW_;  // workspace: M times the block being orthogonalized
  MatrixXd H_;
  Index locked_ = 0;  // Q[:, 0:locked]: converged Ritz vectors, H diagonal and uncoupled there
  Index p_ = 0;       // basis columns whose image under Op is represented in H
  Index r_ = 0;       // residual block Q[:, p:p+r]; 0 when the Krylov space is exhausted
  long applications_ = 0;
  int restarts_ = 0;  // thick restarts and multiplicity-check rounds
  bool verifying_ = false;
  double theta_reference_ = 0.0;  // lowest wanted theta when the current check round began
};

// MV := C^-1 MV, i.e. Op V from M V.
void ThickRestartLanczos::apply_to_mass_product(Eigen::Ref<MatrixXd> MV) {
  applications_ += MV.cols();
  factor_.solve_in_place(MV);
}

MatrixXd ThickRestartLanczos::random_range_block(Index cols) {
  MatrixXd W(n_, cols);
  mass(random_.next(n_, cols), W);
  apply_to_mass_product(W);
  return W;
}

// MW = M W (M is symmetric).
void ThickRestartLanczos::mass(const Eigen::Ref<const MatrixXd>& W, Eigen::Ref<MatrixXd> MW) const {
  symmetric_times(M_, W, MW);
}

// Classical Gram-Schmidt against Q[:, 0:columns], repeated by the DGKS
// criterion; keeps MW = M W. Returns the total coefficients
// (columns x W.cols()).
MatrixXd ThickRestartLanczos::orthogonalize(Eigen::Ref<MatrixXd> W, Eigen::Ref<MatrixXd> MW,
                                           Index columns) const {
  MatrixXd C = MatrixXd::Zero(columns, W.cols());
  if (columns == 0) return C;
  VectorXd before = mass_norms(W, MW);
  MatrixXd G(columns, W.cols());
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    gemm(true, Q_.leftCols(columns), MW, 1.0, 0.0, G);
    gemm(false, Q_.leftCols(columns), G, -1.0, 1.0, W);
    C += G;
    mass(W, MW);
    const VectorXd after = mass_norms(W, MW);
    if ((after.array() >= kRepeatPassRatio * before.array()).all()) break;
    before = after;
  }
  return C;
}

// Appends the M-orthonormalized columns of W (already orthogonal to
// Q[:, 0:start]; MW = M W) at Q[:, start:...], their M-images in MR:
// W = Q[:, start:start+k] B with B upper triangular (k x W.cols()). A
// dependent column is replaced by a fresh random direction coupled to
// nothing (B row zero there). Returns k, smaller than W.cols() only when the
// basis spans all of range(Op). W and MW are used as workspace; W may be
// Q[:, start:start+W.cols()] itself (column c is read before any column
// after c is written).
Index ThickRestartLanczos::append_block(Eigen::Ref<MatrixXd> W, Eigen::Ref<MatrixXd> MW, Index start,
                                       const VectorXd& input_norms, MatrixXd& B) {
  B = MatrixXd::Zero(W.cols(), W.cols());
  Index appended = 0;
  bool exhausted = false;
  for (Index c = 0; c < W.cols(); ++c) {
    auto w = W.col(c);
    auto Mw = MW.col(c);
    double beta = std::sqrt(std::max(0.0, w.dot(Mw)));
    for (int pass = 0; pass < 2 && appended > 0; ++pass) {
      const VectorXd g = MR_.leftCols(appended).transpose() * w;
      w.noalias() -= Q_.middleCols(start, appended) * g;
      Mw.noalias() -= MR_.leftCols(appended) * g;
      B.col(c).head(appended) += g;
      const double before = beta;
      beta = std::sqrt(std::max(0.0, w.dot(Mw)));
      if (beta >= kRepeatPassRatio * before) break;  // DGKS, as in orthogonalize
    }
    if (exhausted) continue;  // only its coefficients are still needed
    const Index position = start + appended;
    if (beta < kExtraPassRatio * input_norms[c]) {
      const VectorXd g = Q_.leftCols(position).transpose() * Mw;
      w.noalias() -= Q_.leftCols(position) * g;
      B.col(c).head(appended) += g.tail(appended);
      mass(w, Mw);
      beta = std::sqrt(std::max(0.0, w.dot(Mw)));
    }
    if (beta <= kDeflationRatio * input_norms[c]) {
      exhausted = !append_fresh_column(position, appended);
      if (!exhausted) ++appended;
      continue;
    }
    Q_.col(position) = w / beta;
    MR_.col(appended) = Mw / beta;
    B(appended, c) = beta;
    ++appended;
  }
  B.conservativeResize(appended, W.cols());
  return appended;
}

bool ThickRestartLanczos::append_fresh_column(Index position, Index block_column) {
  VectorXd w = random_range_block(1).col(0);
  VectorXd Mw(n_);
  mass(w, Mw);
  const double initial = std::sqrt(std::max(0.0, w.dot(Mw)));
  // Three passes: the random vector may lie mostly in the basis already.
  for (int pass = 0; pass < 3; ++pass) {
    const VectorXd g = Q_.leftCols(position).transpose() * Mw;
    w.noalias() -= Q_.leftCols(position) * g;
    mass(w, Mw);
  }
  const double beta = std::sqrt(std::max(0.0, w.dot(Mw)));
  if (!(beta > kExhaustionRatio * initial)) return false;
  Q_.col(position) = w / beta;
  MR_.col(block_column) = Mw / beta;
  return true;
}

// A fresh random block, orthogonal to Q[:, 0:p], as the residual block
// (formed in the columns it will occupy).
void ThickRestartLanczos::append_random_block() {
  auto W = Q_.middleCols(p_, s_.block);
  auto MW = MW_.leftCols(s_.block);
  random_.fill(W);
  mass(W, MW);
  W = MW;
  apply_to_mass_product(W);
  mass(W, MW);
  const VectorXd norms = mass_norms(W, MW);
  orthogonalize(W, MW, p_);
  MatrixXd B;
  r_ = append_block(W, MW, p_, norms, B);
}

// Q[:, 0:S.cols()] = Q[:, 0:S.rows()] S in place, one slice of rows at a
// time: a basis-sized temporary would add a basis to the peak memory.
void ThickRestartLanczos::rotate(const MatrixXd& S) {
  MatrixXd slice;
  for (Index row = 0; row < n_; row += kRotationRows) {
    const Index rows = std::min(kRotationRows, n_ - row);
    slice.resize(rows, S.cols());
    gemm(false, Q_.block(row, 0, rows, S.rows()), S, 1.0, 0.0, slice);
    Q_.block(row, 0, rows, S.cols()) = slice;
  }
}

void ThickRestartLanczos::start() {
  p_ = 0;
  append_random_block();
}

// One block Lanczos step: Op applied to the residual block, which joins the
// represented basis; the orthogonalized result becomes the new residual
// block. It is formed in the basis columns it will occupy.
void ThickRestartLanczos::expand() {
  const Index j = p_ + r_;
  auto W = Q_.middleCols(j, r_);
  W = MR_.leftCols(r_);
  apply_to_mass_product(W);
  // First the components the Lanczos relation predicts: along the vectors
  // coupled to the residual block in H (the previous block or, after a
  // restart, the kept Ritz vectors) and along the block itself, whose
  // M-image MR_ is at hand. They carry most of W; once they are off, one
  // pass over the whole basis normally satisfies the DGKS test (two were
  // needed on nearly every step otherwise, each reading the whole basis).
  Index first = 0;
  while (first < p_ && H_.row(first).segment(p_, r_).isZero(0.0)) ++first;
  if (first < p_) {
    gemm(false, Q_.middleCols(first, p_ - first), H_.block(first, p_, p_ - first, r_), -1.0, 1.0, W);
  }
  auto MW = MW_.leftCols(r_);
  mass(W, MW);
  // The reference of the deflation tests in append_block: W still holds its
  // component along the block itself, q' M Op q > 0, so this is never at
  // rounding level, even where the rest of W is.
  const VectorXd norms = mass_norms(W, MW);
  MatrixXd D = MR_.leftCols(r_).transpose() * W;
  W.noalias() -= Q_.middleCols(p_, r_) * D;
  MW.noalias() -= MR_.leftCols(r_) * D;
  D += orthogonalize(W, MW, j).bottomRows(r_);
  H_.block(p_, p_, r_, r_) = 0.5 * (D + D.transpose());
  MatrixXd B;
  const Index appended = append_block(W, MW, j, norms, B);
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
  Index working = 0;  // the leading unconverged wanted pair: the one the iteration works on
  while (working < wanted && converged(ritz, working)) ++working;
  if (working == wanted) return 0;
  const double limit = kRoundingShare * s_.tolerance / std::numeric_limits<double>::epsilon() *
                       ritz.theta[working];
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
// residual block, which moves down to follow them (its M-image in MR_ is
// unchanged).
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
  rotate(S);
  for (Index c = 0; c < r_; ++c) Q_.col(keep + c) = Q_.col(p_ + c);  // keep <= p: no overlap hazard
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
  append_random_block();
  H_.block(p_, 0, H_.rows() - p_, p_).setZero();
  H_.block(0, p_, p_, H_.cols() - p_).setZero();
}

LanczosOutcome ThickRestartLanczos::finish(const RitzPairs& ritz, Index pairs, bool converged,
                                           std::string message) {
  // The Ritz vectors y = Q s replace the leading basis columns, the rest of
  // the basis is released (a shrinking realloc, in place), and each y is
  // purified there, x = Op y / theta = C^-1 (M y) / theta, all in one
  // multi-column solve.
  rotate(ritz.vectors.leftCols(pairs));
  MR_.resize(0, 0);
  MW_.resize(0, 0);
  Q_.conservativeResize(Eigen::NoChange, pairs);
  MatrixXd X(n_, pairs);
  mass(Q_, X);
  apply_to_mass_product(X);
  for (Index c = 0; c < pairs; ++c) Q_.col(c) = X.col(c) / ritz.theta[c];
  LanczosOutcome out;
  out.X = std::move(Q_);
  out.restarts = restarts_;
  out.converged = converged;
  out.message = std::move(message);
  out.applications = applications_;
  if (!converged) {
    out.theta = ritz.theta;
    out.residual = ritz.residual;
  }
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

// Whether the block iteration has already seen every copy of each wanted
// eigenvalue, so that the multiplicity check would only confirm it: a block
// Krylov space from b random vectors holds min(m, b) independent directions
// of an eigenspace of dimension m (the projections of the b start vectors,
// and of every fresh random block after a lock, onto it), so where every
// wanted eigenvalue shows fewer than b converged copies, m equals that count.
// A copy count that reaches b may hide more: check. Never true for b = 1.
bool ThickRestartLanczos::block_saw_every_copy(const RitzPairs& ritz) const {
  for (Index i = 0; i < s_.count; ++i) {
    Index copies = 0;
    for (Index j = 0; j < ritz.theta.size(); ++j) {
      if (converged(ritz, j) && std::abs(ritz.theta[j] - ritz.theta[i]) <= kCopyWidth * std::abs(ritz.theta[i])) {
        ++copies;
      }
    }
    if (copies >= s_.block) return false;
  }
  return true;
}

// The multiplicity check: after convergence, lock the wanted pairs and run
// on from a fresh random block. A copy of a repeated eigenvalue that the
// Krylov space missed (a single start vector spans one direction per
// distinct eigenvalue) shows up as a new Ritz value above the lowest wanted
// one; the round ends once the best new Ritz value is resolved.
ThickRestartLanczos::Check ThickRestartLanczos::check_multiplicities(const RitzPairs& ritz) {
  const Index c = s_.count;
  if (!verifying_ && block_saw_every_copy(ritz)) return Check::confirmed;
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
  // The solves and the basis products are all small or skinny BLAS calls.
  const SerialBlas serial;
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

}  // namespace rigflex::linalg::detail
