#pragma once
// Sparse Cholesky factorization of symmetric positive definite matrices on
// SuiteSparse CHOLMOD, with the symbolic analysis cached: analyze a pattern
// once, then refactorize numerically for every new matrix (or shift) that has
// that pattern. One object serves many solves ("factor once, solve many").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace rigflex::linalg {

// Column-major; symmetric matrices carry BOTH triangles, as fe assembly
// produces them. Only the upper triangle is read by the factorization.
using SpMat = Eigen::SparseMatrix<double>;

// Outcome of a numeric factorization (a numerical outcome, never thrown).
struct FactorStatus {
  bool ok = false;
  std::string message;
  // Original (unpermuted) index of the first non-positive pivot in the
  // elimination order, -1 if ok.
  long failed_column = -1;
  // min over columns k of pivot_k / A_kk (pivot = D_kk of LDL' or L_kk^2 of
  // LL'). Near 1 for diagonally dominant matrices; at rounding level
  // (~1e-15) when A is singular to working precision. 0 if the
  // factorization failed, or if A has a zero diagonal entry.
  double min_relative_pivot = 0.0;
  // Not attempted: the analysis put the factor above set_memory_limit.
  bool over_memory_limit = false;
};

// Which CHOLMOD factorization to use. automatic lets CHOLMOD choose by the
// flop count of the analysis (simplicial LDL' for very sparse factors,
// supernodal LL' with BLAS-3 otherwise); the others force one.
enum class FactorKind { automatic, simplicial, supernodal };

struct FactorStatistics {
  long analyses = 0;        // symbolic analyses performed
  long factorizations = 0;  // numeric factorizations performed
  long solves = 0;          // calls to solve
  long rhs_solved = 0;      // right-hand-side columns solved in total
  double factor_nnz = 0;    // nonzeros of L (from the analysis)
  double factor_flops = 0;  // flop count of one numeric factorization
  double factor_bytes = 0;  // memory held by L's values and indices
  // factor_bytes as the last analysis predicts it, before any numeric
  // factorization (exact for a supernodal factor, within a few percent for
  // a simplicial one).
  double factor_bytes_estimate = 0;
  double analyze_seconds = 0;
  double factorize_seconds = 0;
  double solve_seconds = 0;
};

class SparseCholesky {
 public:
  explicit SparseCholesky(FactorKind kind = FactorKind::automatic);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Symbolic analysis (fill-reducing ordering, elimination tree, supernodes)
  // of the upper triangle of `pattern` plus the diagonal; values are ignored.
  // Throws std::invalid_argument if `pattern` is not square, std::runtime_error
  // if CHOLMOD fails (out of memory).
  void analyze(const SpMat& pattern);

  // Numeric factorization of A. Reuses the analysis when A's upper triangle
  // fits in the analyzed pattern (entries absent from A are taken as zero);
  // otherwise analyzes A first. Non-positive-definite A is reported in the
  // status, not thrown.
  FactorStatus factorize(const SpMat& A);

  // Factorizes K - sigma*M. The union pattern of K and M is analyzed once
  // and reused for every later shift of the same pencil pattern.
  FactorStatus factorize_shifted(const SpMat& K, const SpMat& M, double sigma);

  // Solves A X = B for all columns of B with one CHOLMOD call. Throws
  // std::logic_error if there is no successful factorization,
  // std::invalid_argument if B has the wrong number of rows.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B);
  // Same, overwriting B (a matrix or a block of contiguous columns of one)
  // with X. With a supernodal factor it needs one column of workspace,
  // where solve() needs copies of B: the form for large blocks. Solves run
  // with one OpenBLAS thread (see sparse_cholesky.cpp).
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> B);
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  // Any other dense expression: evaluated, then solved as above.
  template <typename Derived>
  auto solve(const Eigen::MatrixBase<Derived>& B) {
    if constexpr (Derived::ColsAtCompileTime == 1) {
      return solve(Eigen::VectorXd(B));
    } else {
      return solve(Eigen::MatrixXd(B));
    }
  }

  // A numeric factorization whose analysis predicts more than `bytes` of
  // factor is not attempted: its status says so (over_memory_limit). 0: no
  // limit.
  void set_memory_limit(double bytes);
  // Called after every symbolic analysis with the statistics it gives (the
  // factor's nonzeros, flops and bytes): the last moment a caller can report
  // the cost before paying it.
  void on_analysis(std::function<void(const FactorStatistics&)> callback);

  bool analyzed() const;
  bool factorized() const;  // last factorization succeeded
  Eigen::Index rows() const;
  // sigma of the last successful factorize_shifted; empty after factorize().
  std::optional<double> shift() const;
  const FactorStatistics& statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rigflex::linalg
