// CHOLMOD wrapper: long-index API (cholmod_l_*), symbolic analysis cached in
// a private copy of the upper-triangle pattern whose values are refilled for
// each numeric factorization.
#include "reduction/sparse_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rigflex::reduction {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Sorted upper-triangle pattern (row <= column) of the union of the given
// matrices, always including the full diagonal so that any later shift or
// regularization fits into the same analysis.
struct UpperPattern {
  std::vector<SuiteSparse_long> colptr;
  std::vector<SuiteSparse_long> rows;
};

UpperPattern upper_pattern(std::initializer_list<const SpMat*> matrices, Eigen::Index n) {
  UpperPattern p;
  p.colptr.reserve(static_cast<size_t>(n) + 1);
  p.colptr.push_back(0);
  std::vector<SuiteSparse_long> col;
  for (Eigen::Index j = 0; j < n; ++j) {
    col.clear();
    col.push_back(j);
    for (const SpMat* m : matrices) {
      for (SpMat::InnerIterator it(*m, j); it; ++it) {
        if (it.row() < j) col.push_back(it.row());
      }
    }
    std::sort(col.begin(), col.end());
    col.erase(std::unique(col.begin(), col.end()), col.end());
    p.rows.insert(p.rows.end(), col.begin(), col.end());
    p.colptr.push_back(static_cast<SuiteSparse_long>(p.rows.size()));
  }
  return p;
}

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
    if (A != nullptr) cholmod_l_free_sparse(&A, &common);
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

  void analyze(std::initializer_list<const SpMat*> matrices);
  bool fill(const SpMat& X, double scale);  // false if X leaves the pattern
  FactorStatus factorize_filled();
  FactorStatus scan_pivots() const;
  double pivot(SuiteSparse_long k) const;
  double factor_bytes() const;

  FactorKind kind;
  cholmod_common common{};
  cholmod_sparse* A = nullptr;  // analyzed upper pattern; values refilled per factorization
  cholmod_factor* L = nullptr;
  cholmod_dense* X = nullptr;  // solve workspaces, reused between calls
  cholmod_dense* Y = nullptr;
  cholmod_dense* E = nullptr;
  Eigen::Index n = 0;
  bool factorized = false;
  std::optional<double> shift;
  FactorStatistics stats;
};

void SparseCholesky::Impl::analyze(std::initializer_list<const SpMat*> matrices) {
  const auto start = Clock::now();
  const Eigen::Index size = (*matrices.begin())->rows();
  for (const SpMat* m : matrices) {
    if (m->rows() != m->cols() || m->rows() != size) {
      throw std::invalid_argument("SparseCholesky: matrices must be square and of equal size");
    }
  }
  const UpperPattern p = upper_pattern(matrices, size);
  free_factor();
  if (A != nullptr) cholmod_l_free_sparse(&A, &common);
  A = cholmod_l_allocate_sparse(static_cast<size_t>(size), static_cast<size_t>(size),
                                p.rows.size(), /*sorted=*/1, /*packed=*/1, /*stype=*/1,
                                CHOLMOD_REAL, &common);
  if (A == nullptr) throw std::runtime_error(cholmod_status_text(common.status));
  std::copy(p.colptr.begin(), p.colptr.end(), static_cast<SuiteSparse_long*>(A->p));
  std::copy(p.rows.begin(), p.rows.end(), static_cast<SuiteSparse_long*>(A->i));
  std::fill_n(static_cast<double*>(A->x), p.rows.size(), 0.0);
  L = cholmod_l_analyze(A, &common);
  if (L == nullptr) throw std::runtime_error(cholmod_status_text(common.status));
  n = size;
  shift.reset();
  ++stats.analyses;
  stats.factor_nnz = common.lnz;
  stats.factor_flops = common.fl;
  stats.analyze_seconds += seconds_since(start);
}

bool SparseCholesky::Impl::fill(const SpMat& Xs, double scale) {
  const auto* colptr = static_cast<const SuiteSparse_long*>(A->p);
  const auto* rows = static_cast<const SuiteSparse_long*>(A->i);
  auto* values = static_cast<double*>(A->x);
  for (Eigen::Index j = 0; j < n; ++j) {
    const SuiteSparse_long* first = rows + colptr[j];
    const SuiteSparse_long* last = rows + colptr[j + 1];
    for (SpMat::InnerIterator it(Xs, j); it; ++it) {
      if (it.row() > j) continue;
      const SuiteSparse_long* pos = std::lower_bound(first, last, SuiteSparse_long{it.row()});
      if (pos == last || *pos != it.row()) return false;
      values[pos - rows] += scale * it.value();
    }
  }
  return true;
}

double SparseCholesky::Impl::pivot(SuiteSparse_long k) const {
  const auto* x = static_cast<const double*>(L->x);
  if (L->is_super) {
    const auto* super = static_cast<const SuiteSparse_long*>(L->super);
    const auto* pi = static_cast<const SuiteSparse_long*>(L->pi);
    const auto* px = static_cast<const SuiteSparse_long*>(L->px);
    // Supernode s holds columns super[s]..super[s+1]-1 as a dense
    // column-major block with pi[s+1]-pi[s] rows; diagonal entries first.
    const SuiteSparse_long s =
        std::upper_bound(super, super + L->nsuper + 1, k) - super - 1;
    const SuiteSparse_long nsrow = pi[s + 1] - pi[s];
    const SuiteSparse_long jj = k - super[s];
    const double d = x[px[s] + jj * nsrow + jj];
    return d * d;
  }
  const double d = x[static_cast<const SuiteSparse_long*>(L->p)[k]];
  return L->is_ll ? d * d : d;
}

FactorStatus SparseCholesky::Impl::scan_pivots() const {
  // CHOLMOD's LDL' does not stop at negative pivots, and its LL' reports the
  // failure in the permuted order: one scan gives both the same meaning.
  FactorStatus status;
  const auto* perm = static_cast<const SuiteSparse_long*>(L->Perm);
  const auto* colptr = static_cast<const SuiteSparse_long*>(A->p);
  const auto* values = static_cast<const double*>(A->x);
  const auto limit = static_cast<SuiteSparse_long>(std::min<size_t>(L->minor, L->n));
  double min_ratio = std::numeric_limits<double>::infinity();
  for (SuiteSparse_long k = 0; k < limit; ++k) {
    const SuiteSparse_long original = perm != nullptr ? perm[k] : k;
    const double d = pivot(k);
    if (!(d > 0.0)) {
      status.failed_column = original;
      break;
    }
    const double a = values[colptr[original + 1] - 1];  // diagonal: last in its upper column
    min_ratio = std::min(min_ratio, a > 0.0 ? d / a : 0.0);
  }
  if (status.failed_column < 0 && limit < static_cast<SuiteSparse_long>(L->n)) {
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
  const double word = sizeof(SuiteSparse_long);
  if (L->is_super) {
    return static_cast<double>(L->xsize) * sizeof(double) + static_cast<double>(L->ssize) * word +
           3.0 * static_cast<double>(L->nsuper + 1) * word;
  }
  return static_cast<double>(L->nzmax) * (sizeof(double) + word) +
         4.0 * static_cast<double>(L->n) * word;
}

FactorStatus SparseCholesky::Impl::factorize_filled() {
  const auto start = Clock::now();
  factorized = false;
  const int done = cholmod_l_factorize(A, L, &common);
  ++stats.factorizations;
  stats.factorize_seconds += seconds_since(start);
  if (!done || (common.status < CHOLMOD_OK)) {
    FactorStatus status;
    status.message = cholmod_status_text(common.status);
    return status;
  }
  stats.factor_bytes = factor_bytes();
  FactorStatus status = scan_pivots();
  factorized = status.ok;
  return status;
}

SparseCholesky::SparseCholesky(FactorKind kind) : impl_(std::make_unique<Impl>(kind)) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const SpMat& pattern) {
  if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
  impl_->analyze({&pattern});
}

FactorStatus SparseCholesky::factorize(const SpMat& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("SparseCholesky: matrix must be square");
  if (!analyzed() || A.rows() != impl_->n) analyze(A);
  Impl& d = *impl_;
  std::fill_n(static_cast<double*>(d.A->x), d.A->nzmax, 0.0);
  if (!d.fill(A, 1.0)) {
    d.analyze({&A});
    d.fill(A, 1.0);
  }
  d.shift.reset();
  return d.factorize_filled();
}

FactorStatus SparseCholesky::factorize_shifted(const SpMat& K, const SpMat& M, double sigma) {
  if (!analyzed() || K.rows() != impl_->n) {
    if (!impl_) impl_ = std::make_unique<Impl>(FactorKind::automatic);
    impl_->analyze({&K, &M});
  }
  Impl& d = *impl_;
  if (M.rows() != d.n || M.cols() != d.n || K.cols() != d.n) {
    throw std::invalid_argument("SparseCholesky: K and M must be square and of equal size");
  }
  auto refill = [&] {
    std::fill_n(static_cast<double*>(d.A->x), d.A->nzmax, 0.0);
    return d.fill(K, 1.0) && d.fill(M, -sigma);
  };
  if (!refill()) {
    d.analyze({&K, &M});
    refill();
  }
  FactorStatus status = d.factorize_filled();
  if (status.ok) d.shift = sigma;
  return status;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) {
  if (!factorized()) throw std::logic_error("SparseCholesky::solve: no successful factorization");
  Impl& d = *impl_;
  if (B.rows() != d.n) throw std::invalid_argument("SparseCholesky::solve: wrong number of rows");
  if (B.cols() == 0) return Eigen::MatrixXd(d.n, 0);
  const auto start = Clock::now();
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(B.rows());
  rhs.ncol = static_cast<size_t>(B.cols());
  rhs.nzmax = rhs.nrow * rhs.ncol;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(B.data());  // read only by CHOLMOD
  rhs.z = nullptr;
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_l_solve2(CHOLMOD_A, d.L, &rhs, nullptr, &d.X, nullptr, &d.Y, &d.E, &d.common)) {
    throw std::runtime_error("SparseCholesky::solve: " + cholmod_status_text(d.common.status));
  }
  Eigen::MatrixXd result =
      Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>(
          static_cast<const double*>(d.X->x), B.rows(), B.cols(),
          Eigen::OuterStride<>(static_cast<Eigen::Index>(d.X->d)));
  ++d.stats.solves;
  d.stats.rhs_solved += B.cols();
  d.stats.solve_seconds += seconds_since(start);
  return result;
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

}  // namespace rigflex::reduction
