// CHOLMOD wrapper: long-index API (cholmod_l_*).
//
// Memory is the point of most of what follows: the factor is the largest
// object of a modal analysis, and what sits beside it while it is computed
// or used decides the peak. So nothing besides the factor is kept between
// calls (a supernodal factor's own row structure tells whether a new matrix
// fits its analysis), and the matrix to factorize, K - sigma M, is written
// once, directly in the permuted lower-triangular form that CHOLMOD's
// supernodal kernel reads, instead of a copy that cholmod_factorize would
// permute into a second one.
#include "linalg/sparse_cholesky.hpp"

#include <cholmod.h>
#include <malloc.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "linalg/block_kernels.hpp"
#include "linalg/stopwatch.hpp"

namespace rigflex::linalg {
namespace {

using Clock = std::chrono::steady_clock;
using Long = SuiteSparse_long;

// One term scale * A of the matrix to factorize.
struct Term {
  const SpMat* matrix;
  double scale;
};

// Column j of sum scale_t A_t (one or two terms) restricted to rows i <= j,
// in ascending row order, each row once, the diagonal always (0 if absent,
// so that any later shift fits the same analysis). Relies on Eigen's sorted
// inner indices.
template <typename Visit>
void for_each_upper(const std::vector<Term>& terms, Eigen::Index j, Visit&& visit) {
  struct Cursor {
    const SpMat::StorageIndex* rows;
    const double* values;
    Eigen::Index pos, end;
    double scale;
  };
  std::array<Cursor, 2> cursors{};
  size_t count = 0;
  for (const Term& t : terms) {
    const SpMat& m = *t.matrix;
    const Eigen::Index begin = m.outerIndexPtr()[j];
    const Eigen::Index end =
        m.isCompressed() ? m.outerIndexPtr()[j + 1] : begin + m.innerNonZeroPtr()[j];
    cursors[count++] = {m.innerIndexPtr(), m.valuePtr(), begin, end, t.scale};
  }
  bool diagonal_seen = false;
  while (true) {
    Eigen::Index row = j + 1;
    for (size_t c = 0; c < count; ++c) {
      const Cursor& k = cursors[c];
      if (k.pos < k.end) row = std::min<Eigen::Index>(row, k.rows[k.pos]);
    }
    if (row > j) break;
    double value = 0.0;
    for (size_t c = 0; c < count; ++c) {
      Cursor& k = cursors[c];
      if (k.pos < k.end && k.rows[k.pos] == row) value += k.scale * k.values[k.pos++];
    }
    diagonal_seen = diagonal_seen || row == j;
    visit(row, value);
  }
  if (!diagonal_seen) visit(j, 0.0);
}

// The lower triangle of P A P' (P the fill-reducing permutation, given as
// its inverse: original index -> position; identity if empty) in column
// form, with values (or the pattern only). Under the identity the rows of
// each column come out sorted; permuted, they do not, and nothing that
// reads them needs them to be.
cholmod_sparse* permuted_lower(const std::vector<Term>& terms, Eigen::Index n,
                               const std::vector<Long>& inverse_perm, bool values,
                               cholmod_common& common) {
  auto position = [&](Eigen::Index i) {
    return inverse_perm.empty() ? static_cast<Long>(i) : inverse_perm[static_cast<size_t>(i)];
  };
  // Counting pass into p[c + 1], then p[c] serves as the insertion cursor
  // of column c and ends at the start of column c + 1.
  std::vector<Long> counts(static_cast<size_t>(n) + 1, 0);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Long pj = position(j);
    for_each_upper(terms, j, [&](Eigen::Index i, double) {
      ++counts[static_cast<size_t>(std::min(position(i), pj)) + 1];
    });
  }
  for (size_t c = 1; c < counts.size(); ++c) counts[c] += counts[c - 1];
  const auto nnz = static_cast<size_t>(counts.back());
  cholmod_sparse* S = cholmod_l_allocate_sparse(static_cast<size_t>(n), static_cast<size_t>(n), nnz,
                                                /*sorted=*/0, /*packed=*/1, /*stype=*/-1,
                                                values ? CHOLMOD_REAL : CHOLMOD_PATTERN, &common);
  if (S == nullptr) return nullptr;
  S->sorted = inverse_perm.empty();
  auto* p = static_cast<Long*>(S->p);
  auto* rows = static_cast<Long*>(S->i);
  auto* x = static_cast<double*>(S->x);
  std::copy(counts.begin(), counts.end(), p);
  counts = {};
  for (Eigen::Index j = 0; j < n; ++j) {
    const Long pj = position(j);
    for_each_upper(terms, j, [&](Eigen::Index i, double value) {
      const Long pi = position(i);
      const Long at = p[std::min(pi, pj)]++;
      rows[at] = std::max(pi, pj);
      if (values) x[at] = value;
    });
  }
  for (Eigen::Index c = n; c > 0; --c) p[c] = p[c - 1];
  p[0] = 0;
  return S;
}

// glibc keeps freed heap memory resident for reuse, and what the analysis
// and the factorization free (the ordering's workspace, the copy of the
// matrix) is as large as a good part of the factor: handed back to the
// system, it does not add to the peak of what follows (a Lanczos basis is
// one large fresh allocation that cannot reuse it).
void release_freed_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

struct SparseDeleter {
  cholmod_common* common;
  void operator()(cholmod_sparse* S) const { cholmod_l_free_sparse(&S, common); }
};
using SparseHandle = std::unique_ptr<cholmod_sparse, SparseDeleter>;

int cholmod_kind(FactorKind kind) {
  switch (kind) {
    case FactorKind::simplicial: return CHOLMOD_SIMPLICIAL;
    case FactorKind::supernodal: return CHOLMOD_SUPERNODAL;
    case FactorKind::automatic: break;
  }
  return CHOLMOD_AUTO;
}

std::string cholmod_status_text(int status) {
  switch (status) {
    case CHOLMOD_OUT_OF_MEMORY: return "CHOLMOD ran out of memory";
    case CHOLMOD_TOO_LARGE: return "CHOLMOD: problem too large (integer overflow)";
    case CHOLMOD_INVALID: return "CHOLMOD: invalid input";
    case CHOLMOD_NOT_INSTALLED: return "CHOLMOD: method not installed";
    case CHOLMOD_GPU_PROBLEM: return "CHOLMOD: GPU problem";
    case CHOLMOD_NOT_POSDEF: return "matrix is not positive definite";
    case CHOLMOD_DSMALL: return "CHOLMOD: tiny diagonal entry in the factor";
    default: return "CHOLMOD status " + std::to_string(status);
  }
}

}  // namespace

struct SparseCholesky::Impl {
  explicit Impl(FactorKind k) : kind(k) {
    cholmod_l_start(&common);
    common.print = 0;               // library code never prints
    common.error_handler = nullptr;  // status is read from common.status
    common.supernodal = cholmod_kind(kind);
  }
  ~Impl() {
    free_factor();
    cholmod_l_free_dense(&X, &common);
    cholmod_l_free_dense(&Y, &common);
    cholmod_l_free_dense(&E, &common);
    cholmod_l_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void free_factor() {
    if (L != nullptr) cholmod_l_free_factor(&L, &common);
    factorized = false;
  }

  void analyze(const std::vector<Term>& terms, Eigen::Index size);
  bool fits(const cholmod_sparse& S) const;
  FactorStatus factorize(const std::vector<Term>& terms);
  SparseHandle lower(const std::vector<Term>& terms);
  FactorStatus scan_pivots(const Eigen::VectorXd& diagonal) const;
  double pivot(Long k) const;
  double factor_bytes() const;
  std::vector<Long> inverse_permutation() const;

  FactorKind kind;
  cholmod_common common{};
  cholmod_factor* L = nullptr;
  // Pattern (lower triangle, original order) of the last analysis, kept for
  // a simplicial factor only: its symbolic form has no row structure to
  // test a new matrix against (a supernodal one has, and keeps nothing here).
  std::vector<Long> pattern_colptr, pattern_rows;
  cholmod_dense* X = nullptr;  // solve workspaces, reused between calls
  cholmod_dense* Y = nullptr;
  cholmod_dense* E = nullptr;
  Eigen::Index n = 0;
  bool factorized = false;
  std::optional<double> shift;
  FactorStatistics stats;
  double memory_limit = 0;
  std::function<void(const FactorStatistics&)> analysis_callback;
};

void SparseCholesky::Impl::analyze(const std::vector<Term>& terms, Eigen::Index size) {
  const auto start = Clock::now();
  for (const Term& t : terms) {
    if (t.matrix->rows() != t.matrix->cols() || t.matrix->rows() != size) {
      throw std::invalid_argument("SparseCholesky: matrices must be square and of equal size");
    }
  }
  free_factor();
  pattern_colptr = {};
  pattern_rows = {};
  // The pattern alone, no values: the analysis needs nothing else.
  SparseHandle pattern(permuted_lower(terms, size, {}, false, common), SparseDeleter{&common});
  if (!pattern) throw std::runtime_error(cholmod_status_text(common.status));
  L = cholmod_l_analyze(pattern.get(), &common);
  if (L == nullptr) throw std::runtime_error(cholmod_status_text(common.status));
  if (!L->is_super) {
    const auto* p = static_cast<const Long*>(pattern->p);
    const auto* i = static_cast<const Long*>(pattern->i);
    pattern_colptr.assign(p, p + size + 1);
    pattern_rows.assign(i, i + pattern_colptr.back());
  }
  pattern.reset();
  release_freed_memory();
  n = size;
  shift.reset();
  ++stats.analyses;
  stats.factor_nnz = common.lnz;
  stats.factor_flops = common.fl;
  // A supernodal analysis sizes the factor exactly; a simplicial one counts
  // L's nonzeros, each a value and a row index.
  stats.factor_bytes_estimate =
      L->is_super ? factor_bytes()
                  : common.lnz * (sizeof(double) + sizeof(Long)) + 4.0 * static_cast<double>(n) * sizeof(Long);
  stats.analyze_seconds += seconds_since(start);
  if (analysis_callback) analysis_callback(stats);
}

std::vector<Long> SparseCholesky::Impl::inverse_permutation() const {
  std::vector<Long> inverse(static_cast<size_t>(n));
  const auto* perm = static_cast<const Long*>(L->Perm);
  for (Long k = 0; k < static_cast<Long>(n); ++k) {
    inverse[static_cast<size_t>(perm != nullptr ? perm[k] : k)] = k;
  }
  return inverse;
}

// The matrix in the form the numeric factorization reads: tril(P A P') for
// cholmod_l_super_numeric, or tril(A) for cholmod_l_factorize (simplicial,
// where it makes the one permuted copy that its kernel needs).
SparseHandle SparseCholesky::Impl::lower(const std::vector<Term>& terms) {
  SparseHandle S(permuted_lower(terms, n, L->is_super ? inverse_permutation() : std::vector<Long>{},
                                true, common),
                 SparseDeleter{&common});
  if (!S) throw std::runtime_error(cholmod_status_text(common.status));
  return S;
}

// Whether every entry of S lies in the analyzed structure. The supernodal
// kernel assigns an entry outside it to a wrong place without notice, so
// this is checked before every factorization.
bool SparseCholesky::Impl::fits(const cholmod_sparse& S) const {
  const auto* sp = static_cast<const Long*>(S.p);
  const auto* si = static_cast<const Long*>(S.i);
  if (L->is_super) {
    const auto* super = static_cast<const Long*>(L->super);
    const auto* pi = static_cast<const Long*>(L->pi);
    const auto* ls = static_cast<const Long*>(L->s);
    std::vector<Long> mark(static_cast<size_t>(n), -1);
    for (Long s = 0; s < static_cast<Long>(L->nsuper); ++s) {
      for (Long q = pi[s]; q < pi[s + 1]; ++q) mark[static_cast<size_t>(ls[q])] = s;
      for (Long k = super[s]; k < super[s + 1]; ++k) {
        for (Long q = sp[k]; q < sp[k + 1]; ++q) {
          if (mark[static_cast<size_t>(si[q])] != s) return false;
        }
      }
    }
    return true;
  }
  // Simplicial: S and the analyzed pattern are both unpermuted lower
  // triangles with sorted columns.
  for (Long c = 0; c < static_cast<Long>(n); ++c) {
    const Long* first = pattern_rows.data() + pattern_colptr[static_cast<size_t>(c)];
    const Long* last = pattern_rows.data() + pattern_colptr[static_cast<size_t>(c) + 1];
    for (Long q = sp[c]; q < sp[c + 1]; ++q) {
      first = std::lower_bound(first, last, si[q]);
      if (first == last || *first != si[q]) return false;
    }
  }
  return true;
}

double SparseCholesky::Impl::pivot(Long k) const {
  const auto* x = static_cast<const double*>(L->x);
  if (L->is_super) {
    const auto* super = static_cast<const Long*>(L->super);
    const auto* pi = static_cast<const Long*>(L->pi);
    const auto* px = static_cast<const Long*>(L->px);
    // Supernode s holds columns super[s]..super[s+1]-1 as a dense
    // column-major block with pi[s+1]-pi[s] rows; diagonal entries first.
    const Long s = std::upper_bound(super, super + L->nsuper + 1, k) - super - 1;
    const Long nsrow = pi[s + 1] - pi[s];
    const Long jj = k - super[s];
    const double d = x[px[s] + jj * nsrow + jj];
    return d * d;
  }
  const double d = x[static_cast<const Long*>(L->p)[k]];
  return L->is_ll ? d * d : d;
}

FactorStatus SparseCholesky::Impl::scan_pivots(const Eigen::VectorXd& diagonal) const {
  // CHOLMOD's LDL' does not stop at negative pivots, and its LL' reports the
  // failure in the permuted order: one scan gives both the same meaning.
  FactorStatus status;
  const auto* perm = static_cast<const Long*>(L->Perm);
  const auto limit = static_cast<Long>(std::min<size_t>(L->minor, L->n));
  double min_ratio = std::numeric_limits<double>::infinity();
  for (Long k = 0; k < limit; ++k) {
    const Long original = perm != nullptr ? perm[k] : k;
    const double d = pivot(k);
    if (!(d > 0.0)) {
      status.failed_column = original;
      break;
    }
    const double a = diagonal[original];
    min_ratio = std::min(min_ratio, a > 0.0 ? d / a : 0.0);
  }
  if (status.failed_column < 0 && limit < static_cast<Long>(L->n)) {
    status.failed_column = perm != nullptr ? perm[limit] : limit;
  }
  status.ok = status.failed_column < 0;
  status.min_relative_pivot = status.ok ? (n > 0 ? min_ratio : 1.0) : 0.0;
  status.message = status.ok ? "ok"
                             : "matrix is not positive definite: non-positive pivot at column " +
                                   std::to_string(status.failed_column);
  return status;
}

double SparseCholesky::Impl::factor_bytes() const {
  const double word = sizeof(Long);
  if (L->is_super) {
    return static_cast<double>(L->xsize) * sizeof(double) + static_cast<double>(L->ssize) * word +
           3.0 * static_cast<double>(L->nsuper + 1) * word;
  }
  return static_cast<double>(L->nzmax) * (sizeof(double) + word) +
         4.0 * static_cast<double>(L->n) * word;
}

FactorStatus SparseCholesky::Impl::factorize(const std::vector<Term>& terms) {
  const auto start = Clock::now();
  factorized = false;
  SparseHandle S = lower(terms);
  if (!fits(*S)) {
    S.reset();
    analyze(terms, n);
    S = lower(terms);
  }
  if (memory_limit > 0 && stats.factor_bytes_estimate > memory_limit) {
    FactorStatus status;
    status.over_memory_limit = true;
    status.message = "the factor would need " + std::to_string(std::lround(stats.factor_bytes_estimate / 1048576.0)) +
                     " MiB (" + std::to_string(std::llround(stats.factor_nnz)) + " nonzeros), above the limit of " +
                     std::to_string(std::lround(memory_limit / 1048576.0)) + " MiB";
    return status;
  }
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
  for (const Term& t : terms) diagonal += t.scale * t.matrix->diagonal();
  int done = 0;
  if (L->is_super) {
    double beta[2] = {0.0, 0.0};
    done = cholmod_l_super_numeric(S.get(), nullptr, beta, L, &common);
  } else {
    done = cholmod_l_factorize(S.get(), L, &common);
  }
  S.reset();
  // CHOLMOD keeps its integer workspace (several n-vectors) between calls;
  // the solves do not use it.
  cholmod_l_free_work(&common);
  release_freed_memory();
  ++stats.factorizations;
  stats.factorize_seconds += seconds_since(start);
  if (!done || common.status < CHOLMOD_OK) {
    FactorStatus status;
    status.message = cholmod_status_text(common.status);
    return status;
  }
  stats.factor_bytes = factor_bytes();
  FactorStatus status = scan_pivots(diagonal);
  factorized = status.ok;
  return status;
}

SparseCholesky::SparseCholesky(FactorKind kind) : impl_(std::make_unique<Impl>(kind)) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::set_memory_limit(double bytes) {
  if (!(bytes >= 0)) throw std::invalid_argument("SparseCholesky: the memory limit must be >= 0 bytes");
  if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
  impl_->memory_limit = bytes;
}

void SparseCholesky::on_analysis(std::function<void(const FactorStatistics&)> callback) {
  if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
  impl_->analysis_callback = std::move(callback);
}

void SparseCholesky::analyze(const SpMat& pattern) {
  if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
  impl_->analyze({{&pattern, 1.0}}, pattern.rows());
}

FactorStatus SparseCholesky::factorize(const SpMat& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("SparseCholesky: matrix must be square");
  const std::vector<Term> terms{{&A, 1.0}};
  if (!analyzed() || A.rows() != impl_->n) {
    if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
    impl_->analyze(terms, A.rows());
  }
  impl_->shift.reset();
  return impl_->factorize(terms);
}

FactorStatus SparseCholesky::factorize_shifted(const SpMat& K, const SpMat& M, double sigma) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    throw std::invalid_argument("SparseCholesky: K and M must be square and of equal size");
  }
  const std::vector<Term> terms{{&K, 1.0}, {&M, -sigma}};
  if (!analyzed() || K.rows() != impl_->n) {
    if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
    impl_->analyze(terms, K.rows());
  }
  impl_->shift.reset();
  FactorStatus status = impl_->factorize(terms);
  if (status.ok) impl_->shift = sigma;
  return status;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) {
  Eigen::MatrixXd X = B;
  solve_in_place(X);
  return X;
}

void SparseCholesky::solve_in_place(Eigen::Ref<Eigen::MatrixXd> B) {
  if (!factorized()) throw std::logic_error("SparseCholesky::solve: no successful factorization");
  Impl& d = *impl_;
  if (B.rows() != d.n) throw std::invalid_argument("SparseCholesky::solve: wrong number of rows");
  if (B.cols() == 0) return;
  const auto start = Clock::now();
  // One thread: a triangular solve is a chain of small kernels, one per
  // supernode, that OpenBLAS's threads slow down (see block_kernels.hpp).
  const detail::SerialBlas serial;
  cholmod_dense block{};
  block.nrow = static_cast<size_t>(B.rows());
  block.ncol = static_cast<size_t>(B.cols());
  block.d = static_cast<size_t>(B.outerStride());
  block.nzmax = block.d * block.ncol;
  block.x = B.data();
  block.xtype = CHOLMOD_REAL;
  block.dtype = CHOLMOD_DOUBLE;
  if (d.L->is_super) {
    // What cholmod_solve2 does, minus its two copies of B: permute in
    // place, the two triangular solves, permute back.
    const size_t workspace = block.ncol * d.L->maxesize;
    if (d.E == nullptr || d.E->nzmax < workspace) {
      cholmod_l_free_dense(&d.E, &d.common);
      d.E = cholmod_l_allocate_dense(workspace, 1, workspace, CHOLMOD_REAL, &d.common);
      if (d.E == nullptr) {
        throw std::runtime_error("SparseCholesky::solve: " + cholmod_status_text(d.common.status));
      }
    }
    const auto* perm = static_cast<const Long*>(d.L->Perm);
    Eigen::VectorXd column(d.n);
    for (Eigen::Index c = 0; c < B.cols(); ++c) {
      for (Eigen::Index k = 0; k < d.n; ++k) column[k] = B(perm[k], c);
      B.col(c) = column;
    }
    if (!cholmod_l_super_lsolve(d.L, &block, d.E, &d.common) ||
        !cholmod_l_super_ltsolve(d.L, &block, d.E, &d.common)) {
      throw std::runtime_error("SparseCholesky::solve: " + cholmod_status_text(d.common.status));
    }
    for (Eigen::Index c = 0; c < B.cols(); ++c) {
      column = B.col(c);
      for (Eigen::Index k = 0; k < d.n; ++k) B(perm[k], c) = column[k];
    }
  } else {
    if (!cholmod_l_solve2(CHOLMOD_A, d.L, &block, nullptr, &d.X, nullptr, &d.Y, &d.E, &d.common)) {
      throw std::runtime_error("SparseCholesky::solve: " + cholmod_status_text(d.common.status));
    }
    B = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>(
        static_cast<const double*>(d.X->x), B.rows(), B.cols(),
        Eigen::OuterStride<>(static_cast<Eigen::Index>(d.X->d)));
  }
  ++d.stats.solves;
  d.stats.rhs_solved += B.cols();
  d.stats.solve_seconds += seconds_since(start);
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) {
  return solve(Eigen::MatrixXd(b)).col(0);
}

bool SparseCholesky::analyzed() const { return impl_ && impl_->L != nullptr; }
bool SparseCholesky::factorized() const { return impl_ && impl_->factorized; }
Eigen::Index SparseCholesky::rows() const { return impl_ ? impl_->n : 0; }
std::optional<double> SparseCholesky::shift() const {
  return impl_ ? impl_->shift : std::nullopt;
}
const FactorStatistics& SparseCholesky::statistics() const {
  static const FactorStatistics empty{};
  return impl_ ? impl_->stats : empty;
}

}  // namespace rigflex::linalg
