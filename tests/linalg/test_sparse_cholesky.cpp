#include <dlfcn.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <limits>
#include <stdexcept>
#include <utility>

#include "linalg/sparse_cholesky.hpp"
#include "test_pencils.hpp"

namespace rigflex::linalg {
namespace {

using testing::diagonal_matrix;
using testing::grid_laplacian;
using testing::random_spd;
using testing::uniform;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();

double condition_number(const SpMat& A) {
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig{MatrixXd(A), Eigen::EigenvaluesOnly};
  return eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
}

// Two backward-stable solvers agree to about cond(A) * eps in relative terms;
// the factor 100 covers the growth of rounding with n (a few hundred here).
double solver_agreement(const SpMat& A) { return 100.0 * condition_number(A) * kEps; }

MatrixXd random_block(Index rows, Index cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  MatrixXd B(rows, cols);
  for (Index j = 0; j < cols; ++j)
    for (Index i = 0; i < rows; ++i) B(i, j) = uniform(rng, -1.0, 1.0);
  return B;
}

double relative_difference(const MatrixXd& a, const MatrixXd& b) { return (a - b).norm() / b.norm(); }

class SparseCholeskyKinds : public ::testing::TestWithParam<FactorKind> {};

TEST_P(SparseCholeskyKinds, SolveMatchesEigenSimplicialLDLT) {
  const SpMat A = random_spd(400, 7);
  SparseCholesky chol(GetParam());
  const FactorStatus status = chol.factorize(A);
  ASSERT_TRUE(status.ok) << status.message;
  EXPECT_EQ(status.failed_column, -1);
  const MatrixXd B = random_block(400, 6, 11);
  const Eigen::SimplicialLDLT<SpMat> reference(A);
  EXPECT_LE(relative_difference(chol.solve(B), reference.solve(B)), solver_agreement(A));
  const VectorXd b = B.col(2);
  EXPECT_LE(relative_difference(chol.solve(b), reference.solve(b)), solver_agreement(A));
}

TEST_P(SparseCholeskyKinds, FailedColumnIsTheOriginalIndexOfTheNegativePivot) {
  // Every leading principal submatrix that avoids DOF 123 is positive
  // definite, and the Schur complement at 123 is <= -5 whatever the
  // ordering, so 123 is the first (and only) non-positive pivot.
  SpMat A = random_spd(300, 3);
  A.coeffRef(123, 123) = -5.0;
  SparseCholesky chol(GetParam());
  const FactorStatus status = chol.factorize(A);
  EXPECT_FALSE(status.ok);
  EXPECT_EQ(status.failed_column, 123);
  EXPECT_FALSE(status.message.empty());
  EXPECT_FALSE(chol.factorized());
  EXPECT_THROW(chol.solve(VectorXd::Ones(300)), std::logic_error);
}

TEST_P(SparseCholeskyKinds, ZeroRowFailsAtItsColumn) {
  SpMat A = random_spd(200, 5);
  A.prune([](Index i, Index j, double) { return i != 57 && j != 57; });
  const FactorStatus status = SparseCholesky(GetParam()).factorize(A);
  EXPECT_FALSE(status.ok);
  EXPECT_EQ(status.failed_column, 57);
}

TEST_P(SparseCholeskyKinds, SolveInPlaceOnColumnsOfALargerMatrix) {
  const SpMat A = random_spd(400, 13);
  SparseCholesky chol(GetParam());
  ASSERT_TRUE(chol.factorize(A).ok);
  const MatrixXd B = random_block(400, 7, 17);
  const MatrixXd X = chol.solve(B);
  EXPECT_LE(relative_difference(X, Eigen::SimplicialLDLT<SpMat>(A).solve(B)), solver_agreement(A));
  MatrixXd big = random_block(400, 12, 19);
  const MatrixXd before = big;
  big.middleCols(3, 7) = B;
  chol.solve_in_place(big.middleCols(3, 7));
  EXPECT_TRUE(big.middleCols(3, 7) == X);  // the same arithmetic as solve()
  EXPECT_TRUE(big.leftCols(3) == before.leftCols(3));
  EXPECT_TRUE(big.rightCols(2) == before.rightCols(2));
  EXPECT_EQ(chol.statistics().rhs_solved, 14);
}

TEST_P(SparseCholeskyKinds, MatrixOutsideTheAnalyzedPatternIsReanalyzed) {
  // A supernodal factor is checked against its own row structure, a
  // simplicial one against the analyzed pattern it keeps.
  const SpMat A = random_spd(150, 8);
  SpMat D(150, 150);
  D.setIdentity();
  SparseCholesky chol(GetParam());
  chol.analyze(D);
  ASSERT_TRUE(chol.factorize(A).ok);
  EXPECT_EQ(chol.statistics().analyses, 2);
  const VectorXd b = VectorXd::LinSpaced(150, -1.0, 1.0);
  EXPECT_LE((A * chol.solve(b) - b).norm() / b.norm(), solver_agreement(A));
  // A subset of the pattern (the diagonal) reuses the analysis of A.
  ASSERT_TRUE(chol.factorize(D).ok);
  EXPECT_EQ(chol.statistics().analyses, 2);
  EXPECT_LE((chol.solve(b) - b).norm(), 10 * kEps * b.norm());
  // So does K - sigma M with M inside the pattern of A (its diagonal).
  SpMat M = A;
  M.prune([](Index i, Index j, double) { return i == j; });
  ASSERT_TRUE(chol.factorize_shifted(A, M, -0.5).ok);
  EXPECT_EQ(chol.statistics().analyses, 2);
  const SpMat shifted = A + 0.5 * M;
  EXPECT_LE((shifted * chol.solve(b) - b).norm() / b.norm(), solver_agreement(shifted));
}

// The analysis predicts the factor's memory before the numeric work: the
// prediction the commands print and hold to --max-memory. Exact for a
// supernodal factor (the symbolic supernodes fix its size); for a
// simplicial one L's nonzero count is exact, and the allocation that
// CHOLMOD then makes is at most a few percent larger (it keeps some slack
// per column): 10 % bounds both ways.
TEST_P(SparseCholeskyKinds, TheAnalysisPredictsTheFactorsMemory) {
  const testing::Pencil p = grid_laplacian(40, 40);  // K + M: positive definite
  SparseCholesky chol(GetParam());
  FactorStatistics seen;
  int calls = 0;
  chol.on_analysis([&](const FactorStatistics& s) {
    seen = s;
    ++calls;
  });
  ASSERT_TRUE(chol.factorize_shifted(p.K, p.M, -1.0).ok);
  EXPECT_EQ(calls, 1);
  EXPECT_GT(seen.factor_bytes_estimate, 0.0);
  EXPECT_EQ(seen.factorizations, 0) << "reported before the numeric factorization";
  const double actual = chol.statistics().factor_bytes;
  EXPECT_NEAR(seen.factor_bytes_estimate / actual, 1.0, 0.10) << seen.factor_bytes_estimate << " vs " << actual;
}

// Over the limit, nothing numeric is attempted and the status says why.
TEST_P(SparseCholeskyKinds, AFactorAboveTheMemoryLimitIsNotAttempted) {
  const testing::Pencil p = grid_laplacian(40, 40);
  SparseCholesky probe(GetParam());
  ASSERT_TRUE(probe.factorize_shifted(p.K, p.M, -1.0).ok);
  const double needed = probe.statistics().factor_bytes_estimate;

  SparseCholesky chol(GetParam());
  chol.set_memory_limit(0.5 * needed);
  const FactorStatus refused = chol.factorize_shifted(p.K, p.M, -1.0);
  EXPECT_FALSE(refused.ok);
  EXPECT_TRUE(refused.over_memory_limit);
  EXPECT_NE(refused.message.find("above the limit"), std::string::npos) << refused.message;
  EXPECT_EQ(chol.statistics().factorizations, 0);
  EXPECT_FALSE(chol.factorized());

  chol.set_memory_limit(2.0 * needed);
  const FactorStatus done = chol.factorize_shifted(p.K, p.M, -1.0);
  EXPECT_TRUE(done.ok) << done.message;
  EXPECT_FALSE(done.over_memory_limit);
  EXPECT_THROW(chol.set_memory_limit(-1.0), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Kinds, SparseCholeskyKinds,
                         ::testing::Values(FactorKind::automatic, FactorKind::simplicial,
                                           FactorKind::supernodal));

TEST(SparseCholesky, BlockSolveMatchesColumnSolvesAndCountsThem) {
  const SpMat A = random_spd(500, 21);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A).ok);
  const MatrixXd B = random_block(500, 5, 4);
  const MatrixXd X = chol.solve(B);
  for (Index j = 0; j < B.cols(); ++j) {
    EXPECT_LE(relative_difference(chol.solve(VectorXd(B.col(j))), X.col(j)), solver_agreement(A));
  }
  const FactorStatistics& s = chol.statistics();
  EXPECT_EQ(s.solves, 6);
  EXPECT_EQ(s.rhs_solved, 10);
  EXPECT_EQ(s.analyses, 1);
  EXPECT_EQ(s.factorizations, 1);
  EXPECT_GE(s.factor_nnz, static_cast<double>(A.nonZeros() + A.rows()) / 2.0);
  EXPECT_GT(s.factor_bytes, 8.0 * s.factor_nnz * 0.99);
  EXPECT_GE(s.factorize_seconds, 0.0);
  EXPECT_GE(s.solve_seconds, 0.0);
}

TEST(SparseCholesky, NewShiftReusesTheAnalysis) {
  // Free grid Laplacian (singular K) with a random positive lumped mass:
  // K - sigma M is positive definite for every sigma < 0.
  const testing::Pencil p = grid_laplacian(30, 30);
  std::mt19937_64 rng(5);
  VectorXd m(p.K.rows());
  for (Index i = 0; i < m.size(); ++i) m[i] = uniform(rng, 0.5, 1.5);
  const SpMat M = diagonal_matrix(m);
  SparseCholesky chol(FactorKind::supernodal);
  const MatrixXd B = random_block(p.K.rows(), 3, 9);
  for (const double sigma : {-0.5, -2.0, -1e-3}) {
    const FactorStatus status = chol.factorize_shifted(p.K, M, sigma);
    ASSERT_TRUE(status.ok) << status.message;
    ASSERT_TRUE(chol.shift().has_value());
    EXPECT_EQ(*chol.shift(), sigma);
    const SpMat A = p.K - sigma * M;
    const Eigen::SimplicialLDLT<SpMat> reference(A);
    EXPECT_LE(relative_difference(chol.solve(B), reference.solve(B)), solver_agreement(A));
  }
  EXPECT_EQ(chol.statistics().analyses, 1);
  EXPECT_EQ(chol.statistics().factorizations, 3);
}

TEST(SparseCholesky, RelativePivotFlagsNearSingularMatrices) {
  // tridiag(-1, 4, -1): elimination preserves diagonal dominance, so in any
  // order every pivot is at least 4 - 2, half its diagonal.
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < 100; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 1 < 100) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  SpMat T(100, 100);
  T.setFromTriplets(t.begin(), t.end());
  const FactorStatus good = SparseCholesky().factorize(T);
  ASSERT_TRUE(good.ok);
  EXPECT_GE(good.min_relative_pivot, 0.5);
  // Free Laplacian + 1e-12 I: the last pivot is ~ 1e-12 n / 1 relative to a
  // diagonal of 2..4, far below anything a well-posed matrix shows.
  const testing::Pencil p = grid_laplacian(20, 20);
  SpMat I(400, 400);
  I.setIdentity();
  const FactorStatus near = SparseCholesky().factorize(SpMat(p.K + 1e-12 * I));
  ASSERT_TRUE(near.ok);
  EXPECT_LT(near.min_relative_pivot, 1e-8);
}

TEST(SparseCholesky, MovedFactorizationKeepsWorking) {
  const SpMat A = random_spd(120, 2);
  SparseCholesky first;
  ASSERT_TRUE(first.factorize(A).ok);
  SparseCholesky second(std::move(first));
  EXPECT_TRUE(second.factorized());
  const VectorXd b = VectorXd::Ones(120);
  EXPECT_LE((A * second.solve(b) - b).norm() / b.norm(), solver_agreement(A));
  SparseCholesky third;
  third = std::move(second);
  EXPECT_TRUE(third.factorized());
  EXPECT_EQ(third.rows(), 120);
}

TEST(SparseCholesky, SolvesLeaveTheBlasThreadCountAsTheyFoundIt) {
  // Solves run on one OpenBLAS thread (see sparse_cholesky.cpp) and must
  // give the caller's setting back.
  const auto get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const auto set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (get == nullptr || set == nullptr) GTEST_SKIP() << "the BLAS in this process is not OpenBLAS";
  const int original = get();
  set(2);
  const int two = get();  // 2, or 1 where OpenBLAS was built for one thread
  SparseCholesky chol(FactorKind::supernodal);
  ASSERT_TRUE(chol.factorize(random_spd(300, 23)).ok);
  chol.solve(random_block(300, 3, 29));
  EXPECT_EQ(get(), two);
  set(original);
}

TEST(SparseCholesky, InvalidUseThrows) {
  SparseCholesky chol;
  EXPECT_THROW(chol.solve(VectorXd::Ones(3)), std::logic_error);
  EXPECT_THROW(chol.analyze(SpMat(3, 4)), std::invalid_argument);
  ASSERT_TRUE(chol.factorize(random_spd(10, 1)).ok);
  EXPECT_THROW(chol.solve(VectorXd::Ones(9)), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex::linalg
