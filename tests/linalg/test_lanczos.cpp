// Shift-invert Lanczos against the dense oracle and closed forms, for the
// single-vector (block 1) and the block variant.
//
// Tolerances used throughout, and why:
//  - residual <= 1e-8: convergence is declared at |beta s| <= 1e-10 theta on
//    the transformed problem; after purification x = Op y / theta the pencil
//    residual is ||M r|| / theta^2, i.e. about 1e-10 (lambda - sigma) ||M x||,
//    and relative to ||K x|| ~ lambda ||M x|| that is ~1e-10. The factor 100
//    covers the ratio of ||M||^1/2 to ||M x|| for M-normalized x.
//  - orthogonality <= 1e-10 (the brief's bar; the final Rayleigh-Ritz gives
//    ~1e-15).
//  - eigenvalues 1e-9 relative to the oracle: Ritz values from the final
//    Rayleigh-Ritz are accurate to the square of the vector error, so both
//    solvers sit at rounding level (~1e-13) well inside this.
//  - subspaces: cosines of principal angles >= 1 - 1e-8 per cluster of equal
//    eigenvalues: the angle error is ~ residual / gap, gaps >= 1e-2 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "linalg/block_kernels.hpp"
#include "linalg/eigen_solver.hpp"
#include "linalg/mechanism.hpp"
#include "test_pencils.hpp"

namespace rigflex::linalg {
namespace {

using testing::Pencil;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kResidual = 1e-8;
constexpr double kOrthogonality = 1e-10;
constexpr double kEigenvalue = 1e-9;
constexpr double kSubspace = 1e-8;
constexpr double kClusterGap = 1e-6;

class Lanczos : public ::testing::TestWithParam<int> {
 protected:
  EigenOptions options(int count) const {
    EigenOptions o;
    o.count = count;
    o.method = EigenMethod::lanczos;
    o.block_size = GetParam();
    return o;
  }
};

// Oracle with 10 extra pairs, so that clusters cut by `count` are recognized.
EigenResult oracle(const Pencil& p, int count, double shift) {
  const int extra = std::min<int>(count + 10, static_cast<int>(p.K.rows()));
  EigenResult r = solve_dense(MatrixXd(p.K), MatrixXd(p.M), extra, shift);
  EXPECT_TRUE(r.converged) << r.message;
  return r;
}

// zero_floor: eigenvalues below it are rigid-body modes (see
// expect_valid_pairs) and are compared with an absolute tolerance
// kEigenvalue * zero_floor.
void expect_matches_oracle(const Pencil& p, const EigenResult& r, const EigenResult& ref,
                           int count, double zero_floor) {
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_EQ(r.eigenvalues.size(), count);
  testing::expect_valid_pairs(p, r, kResidual, kOrthogonality, zero_floor);
  testing::expect_same_eigenvalues(r.eigenvalues, ref.eigenvalues.head(count), kEigenvalue, zero_floor);
  testing::expect_same_subspaces(p, r, ref, kClusterGap, kSubspace, zero_floor);
}

// The grid Laplacian's lowest pairs against its closed form. Its zero
// eigenvalue is compared to 1e-10 lambda_2 absolute (on the 40 x 40 grid
// ~6e-13; it comes out at rounding level, ~1e-15).
void expect_grid_modes(const Pencil& p, const EigenResult& r, Index nx, Index ny, int count) {
  ASSERT_TRUE(r.converged) << r.message;
  const VectorXd exact = testing::grid_laplacian_eigenvalues(nx, ny, count);
  testing::expect_valid_pairs(p, r, kResidual, kOrthogonality, 1e-3 * exact[1]);
  testing::expect_same_eigenvalues(r.eigenvalues, exact, 1e-10, exact[1]);
}

TEST_P(Lanczos, RandomPencilMatchesDense) {
  const Pencil p = testing::random_pencil(300, 41, false);
  const EigenResult r = solve_lanczos(p.K, p.M, options(12));
  expect_matches_oracle(p, r, oracle(p, 12, -0.01), 12, 0.0);
  EXPECT_LT(r.shift, 0.0);
  EXPECT_GT(r.operator_applications, 12);
}

TEST_P(Lanczos, SingularMassMatchesDenseWithoutInfiniteEigenvalues) {
  const Pencil p = testing::random_pencil(360, 43, true);  // a third massless
  const EigenResult r = solve_lanczos(p.K, p.M, options(15));
  expect_matches_oracle(p, r, oracle(p, 15, -0.01), 15, 0.0);
}

TEST_P(Lanczos, FindsSevenFoldAndThreeFoldRepeatedEigenvalues) {
  // 1, 2 (x7), 3 (x3), then simple values from 4 to 200.
  VectorXd values(240);
  values << 1.0, VectorXd::Constant(7, 2.0), VectorXd::Constant(3, 3.0),
      VectorXd::LinSpaced(229, 4.0, 200.0);
  for (const bool congruence : {false, true}) {
    SCOPED_TRACE(congruence ? "M = G G'" : "M = I");
    const Pencil p = testing::prescribed_spectrum(values, 77, congruence);
    const EigenResult r = solve_lanczos(p.K, p.M, options(15));
    expect_matches_oracle(p, r, oracle(p, 15, -0.1), 15, 0.0);
    // The prescribed values themselves: K = G Q D Q' G' in floating point
    // perturbs them by ~eps ||K|| cond(G)^2 ~ 1e-13 relative.
    testing::expect_same_eigenvalues(r.eigenvalues, values.head(15), 1e-10, 0.0);
  }
}

// The 12 lowest pairs of a prescribed spectrum with block 4, solved with
// the multiplicity check (EigenOptions::verify_multiplicities) and
// without; the checked run is compared with the oracle and the values.
struct CheckedAndUnchecked {
  EigenResult checked, unchecked;
};
CheckedAndUnchecked solve_with_and_without_check(const VectorXd& values, unsigned seed) {
  const Pencil p = testing::prescribed_spectrum(values, seed, true);
  EigenOptions o;
  o.count = 12;
  o.method = EigenMethod::lanczos;
  o.block_size = 4;
  CheckedAndUnchecked r;
  r.checked = solve_lanczos(p.K, p.M, o);
  o.verify_multiplicities = false;
  r.unchecked = solve_lanczos(p.K, p.M, o);
  expect_matches_oracle(p, r.checked, oracle(p, 12, -0.1), 12, 0.0);
  testing::expect_same_eigenvalues(r.checked.eigenvalues, values.head(12), 1e-10, 0.0);
  return r;
}

// The check is skipped where a block of 4 has seen fewer than 4 copies of
// every wanted eigenvalue: the solve then makes exactly the applications of
// a run without the check, and still finds every copy.
TEST(LanczosMultiplicityCheck, SkippedWhereTheBlockOutnumbersEveryCopyCount) {
  VectorXd values(200);  // 1, 2 (x3), 3 (x2), then simple values from 4 to 100
  values << 1.0, VectorXd::Constant(3, 2.0), VectorXd::Constant(2, 3.0), VectorXd::LinSpaced(194, 4.0, 100.0);
  const CheckedAndUnchecked r = solve_with_and_without_check(values, 79);
  EXPECT_EQ(r.checked.operator_applications, r.unchecked.operator_applications);
}

// A copy count that reaches the block size may hide more copies: the check
// runs (more applications than without it) and finds all six.
TEST(LanczosMultiplicityCheck, RunsWhereACopyCountReachesTheBlock) {
  VectorXd values(200);  // 1, 2 (x6), then simple values from 3 to 100
  values << 1.0, VectorXd::Constant(6, 2.0), VectorXd::LinSpaced(193, 3.0, 100.0);
  const CheckedAndUnchecked r = solve_with_and_without_check(values, 83);
  EXPECT_GT(r.checked.operator_applications, r.unchecked.operator_applications);
}

TEST_P(Lanczos, FreeLatticeHasSixRigidBodyModes) {
  const Pencil p = testing::free_lattice(6, 5, 4);  // 360 DOFs
  const EigenResult r = solve_lanczos(p.K, p.M, options(16));
  const EigenResult ref = oracle(p, 16, -1e-2);
  // Rigid-body lambdas are rounding-level Rayleigh quotients, |lambda| ~
  // eps ||K|| / ||M|| ~ 1e-15; they are compared on an absolute floor of
  // 1e-3 times the first flexible eigenvalue (1e-12 lambda_7 absolute).
  const double floor = 1e-3 * ref.eigenvalues[6];
  expect_matches_oracle(p, r, ref, 16, floor);
  // Those Rayleigh quotients are ~1e-15 here, against lambda_7 ~ 1e-2.
  for (int i = 0; i < 6; ++i) EXPECT_LE(std::abs(r.eigenvalues[i]), 1e-9 * ref.eigenvalues[6]);
  EXPECT_GT(r.eigenvalues[6], 1e-9 * ref.eigenvalues[15]);
}

TEST_P(Lanczos, FreeChainRigidModeAndDoubleRootsOfSquareGrid) {
  // Square 40 x 40 grid Laplacian: one zero eigenvalue, then pairs.
  const Pencil p = testing::grid_laplacian(40, 40);
  const EigenResult r = solve_lanczos(p.K, p.M, options(21));
  expect_grid_modes(p, r, 40, 40, 21);
}

TEST_P(Lanczos, EightMassChainMatchesClosedForm) {
  const Pencil p = testing::spring_chain(8, 1e5, 10.0, false);
  VectorXd f(8);
  for (int j = 1; j <= 8; ++j) {
    f[j - 1] = std::sqrt(1e5 / 10.0) * std::sin(j * std::numbers::pi / 18.0) / std::numbers::pi;
  }
  for (const int count : {3, 8}) {
    SCOPED_TRACE("count " + std::to_string(count));
    const EigenResult r = solve_lanczos(p.K, p.M, options(count));
    ASSERT_TRUE(r.converged) << r.message;
    testing::expect_same_eigenvalues(r.frequencies_hz(), f.head(count), 1e-10, 0.0);
    testing::expect_valid_pairs(p, r, kResidual, kOrthogonality);
  }
}

TEST_P(Lanczos, SameInputSameBits) {
  const Pencil p = testing::random_pencil(250, 5, true);
  EigenOptions o = options(8);
  o.subspace = 8 + 2 * GetParam() + 4;  // forces restarts
  const EigenResult a = solve_lanczos(p.K, p.M, o);
  const EigenResult b = solve_lanczos(p.K, p.M, o);
  ASSERT_TRUE(a.converged) << a.message;
  EXPECT_GT(a.restarts, 0);
  EXPECT_TRUE(a.eigenvalues == b.eigenvalues);
  EXPECT_TRUE(a.vectors == b.vectors);
  EXPECT_EQ(a.operator_applications, b.operator_applications);
  o.seed = 2;
  const EigenResult c = solve_lanczos(p.K, p.M, o);
  testing::expect_same_eigenvalues(c.eigenvalues, a.eigenvalues, kEigenvalue, 0.0);
}

TEST_P(Lanczos, SmallSubspaceRestartsAndReportsProgress) {
  const Pencil p = testing::random_pencil(300, 61, false);
  EigenOptions o = options(10);
  o.subspace = 10 + 2 * GetParam() + 2;
  int calls = 0, last_restart = -1;
  o.progress = [&](const EigenProgress& progress) {
    ++calls;
    EXPECT_GE(progress.restart, last_restart);
    EXPECT_EQ(progress.wanted, 10);
    last_restart = progress.restart;
  };
  const EigenResult r = solve_lanczos(p.K, p.M, o);
  expect_matches_oracle(p, r, oracle(p, 10, -0.01), 10, 0.0);
  EXPECT_GT(r.restarts, 1);
  EXPECT_GT(calls, 1);
}

TEST_P(Lanczos, RestartLimitGivesConvergedPrefixOnly) {
  const Pencil p = testing::random_pencil(300, 67, false);
  EigenOptions o = options(10);
  o.subspace = 10 + GetParam();
  o.max_restarts = 0;
  o.automatic_retry = false;
  const EigenResult r = solve_lanczos(p.K, p.M, o);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(r.converged_count, 10);
  EXPECT_NE(r.message.find("not converged"), std::string::npos) << r.message;
  EXPECT_NE(r.stall.cause, StallCause::none);
  EXPECT_NE(r.message.find(r.stall.advice), std::string::npos) << r.message;
  const EigenResult ref = oracle(p, 10, -0.01);
  testing::expect_same_eigenvalues(r.eigenvalues, ref.eigenvalues.head(r.converged_count),
                                   kEigenvalue, 0.0);
  testing::expect_valid_pairs(p, r, kResidual, kOrthogonality);
}

TEST_P(Lanczos, MoreWantedThanFiniteEigenvalues) {
  const Pencil p = testing::random_pencil(30, 71, true);  // 20 massed DOFs
  const EigenResult r = solve_lanczos(p.K, p.M, options(25));
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.converged_count, 20);
  const EigenResult ref = solve_dense(MatrixXd(p.K), MatrixXd(p.M), 25, -0.01);
  testing::expect_same_eigenvalues(r.eigenvalues, ref.eigenvalues, kEigenvalue, 0.0);
  testing::expect_valid_pairs(p, r, kResidual, kOrthogonality);
}

TEST_P(Lanczos, SupernodalFactorMatchesDense) {
  // The solves on a supernodal factor take another path through CHOLMOD
  // than on the simplicial factor small pencils get by default.
  for (const bool singular_mass : {false, true}) {
    SCOPED_TRACE(singular_mass ? "a third massless" : "M positive definite");
    const Pencil p = testing::random_pencil(300, 103, singular_mass);
    SparseCholesky factor(FactorKind::supernodal);
    ASSERT_TRUE(factor.factorize_shifted(p.K, p.M, -0.01).ok);
    const EigenResult r = solve_lanczos(p.K, p.M, options(12), factor);
    expect_matches_oracle(p, r, oracle(p, 12, -0.01), 12, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(BlockSizes, Lanczos, ::testing::Values(1, 4),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return "block" + std::to_string(info.param);
                         });

// A random pencil with three mechanism DOFs: 17 has neither stiffness nor
// mass, 40 and 41 form a massless hinge (a spring between them only).
Pencil mechanism_pencil() {
  Pencil p = testing::random_pencil(300, 83, false);
  auto isolated = [](Index i, Index j, double) {
    const auto free = [](Index d) { return d == 17 || d == 40 || d == 41; };
    return !free(i) && !free(j);
  };
  p.K.prune(isolated);
  p.M.prune(isolated);
  p.K.coeffRef(40, 40) = 3.0;
  p.K.coeffRef(41, 41) = 3.0;
  p.K.coeffRef(40, 41) = -3.0;
  p.K.coeffRef(41, 40) = -3.0;
  p.K.makeCompressed();
  return p;
}

TEST(LanczosMechanism, SingularShiftedMatrixNamesTheMechanismDofs) {
  const Pencil p = mechanism_pencil();
  const std::vector<Index> expected{17, 40, 41};
  for (const auto method : {EigenMethod::lanczos, EigenMethod::dense}) {
    for (const std::optional<double> shift : {std::optional<double>(), std::optional<double>(-0.01)}) {
      EigenOptions o;
      o.count = 5;
      o.method = method;
      o.shift = shift;
      const EigenResult r = solve_lanczos(p.K, p.M, o);
      EXPECT_FALSE(r.converged);
      EXPECT_EQ(r.converged_count, 0);
      EXPECT_NE(r.message.find("K - sigma M is singular: mechanism"), std::string::npos) << r.message;
      EXPECT_EQ(r.mechanism_dofs, expected);
    }
  }
}

TEST(LanczosMechanism, ShiftAboveTheSpectrumIsNotAMechanism) {
  const Pencil p = testing::random_pencil(300, 89, false);
  EigenOptions o;
  o.count = 4;
  o.method = EigenMethod::lanczos;
  o.shift = 50.0;
  const EigenResult r = solve_lanczos(p.K, p.M, o);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.mechanism_dofs.empty());
  EXPECT_NE(r.message.find("not positive definite"), std::string::npos) << r.message;
}

TEST(LanczosFactorReuse, SameResultAsTheOneCallForm) {
  const Pencil p = testing::random_pencil(300, 97, true);
  EigenOptions o;
  o.count = 6;
  o.method = EigenMethod::lanczos;
  SparseCholesky factor;
  const PencilFactorization pf = factorize_pencil(p.K, p.M, std::nullopt, factor);
  ASSERT_TRUE(pf.ok) << pf.message;
  EXPECT_EQ(pf.shift, default_shift(p.K, p.M));
  const EigenResult reused = solve_lanczos(p.K, p.M, o, factor);
  const EigenResult direct = solve_lanczos(p.K, p.M, o);
  ASSERT_TRUE(reused.converged);
  EXPECT_TRUE(reused.eigenvalues == direct.eigenvalues);
  EXPECT_TRUE(reused.vectors == direct.vectors);
  // The same factorization serves a second, larger request.
  o.count = 9;
  const EigenResult more = solve_lanczos(p.K, p.M, o, factor);
  ASSERT_TRUE(more.converged);
  testing::expect_same_eigenvalues(more.eigenvalues.head(6), direct.eigenvalues, kEigenvalue, 0.0);
  EXPECT_EQ(factor.statistics().factorizations, 1);
}

TEST(LanczosFactorReuse, UnknownOrMismatchedShiftThrows) {
  const Pencil p = testing::random_pencil(250, 3, false);
  EigenOptions o;
  o.count = 3;
  SparseCholesky unshifted;
  ASSERT_TRUE(unshifted.factorize(p.K).ok);
  EXPECT_THROW(solve_lanczos(p.K, p.M, o, unshifted), std::invalid_argument);
  SparseCholesky shifted;
  ASSERT_TRUE(shifted.factorize_shifted(p.K, p.M, -0.5).ok);
  o.shift = -0.25;
  EXPECT_THROW(solve_lanczos(p.K, p.M, o, shifted), std::invalid_argument);
  o.shift = -0.5;
  EXPECT_TRUE(solve_lanczos(p.K, p.M, o, shifted).converged);
  SparseCholesky empty;
  EXPECT_THROW(solve_lanczos(p.K, p.M, o, empty), std::invalid_argument);
}

// The products the iteration runs on blocks of vectors (block_kernels.hpp)
// against Eigen's: widths around the kernel's sweep width, compressed and
// uncompressed storage, transposed and strided operands.
TEST(LanczosKernels, SymmetricProductMatchesEigen) {
  SpMat A = testing::random_spd(200, 107);
  const MatrixXd X = MatrixXd::Random(200, 13);
  for (const bool compressed : {true, false}) {
    if (!compressed) A.uncompress();
    for (const Index width : {1, 8, 11}) {
      MatrixXd AX(200, width);
      detail::symmetric_times(A, X.leftCols(width), AX);
      const MatrixXd reference = A * X.leftCols(width);
      EXPECT_LE((AX - reference).norm(), 1e-14 * reference.norm()) << width;
    }
  }
}

TEST(LanczosKernels, GemmMatchesEigen) {
  const MatrixXd A = MatrixXd::Random(300, 9), B = MatrixXd::Random(300, 5), S = MatrixXd::Random(9, 4);
  MatrixXd C = MatrixXd::Random(9, 5);
  const MatrixXd expected = 2.0 * A.transpose() * B + 0.5 * C;
  detail::gemm(true, A, B, 2.0, 0.5, C);
  EXPECT_LE((C - expected).norm(), 1e-13 * expected.norm());
  MatrixXd D = MatrixXd::Random(300, 10);
  const MatrixXd before = D;
  detail::gemm(false, A.middleRows(0, 300), S, -1.0, 1.0, D.middleCols(2, 4));
  const MatrixXd updated = before.middleCols(2, 4) - A * S;
  EXPECT_LE((D.middleCols(2, 4) - updated).norm(), 1e-13 * updated.norm());
  EXPECT_TRUE(D.leftCols(2) == before.leftCols(2));
  EXPECT_TRUE(D.rightCols(4) == before.rightCols(4));
}

TEST(LanczosAutomatic, SmallProblemsUseTheDenseSolver) {
  const Pencil p = testing::random_pencil(100, 101, true);
  EigenOptions o;
  o.count = 7;
  const EigenResult automatic = solve_lanczos(p.K, p.M, o);
  const EigenResult dense = solve_dense(MatrixXd(p.K), MatrixXd(p.M), 7, default_shift(p.K, p.M));
  ASSERT_TRUE(automatic.converged);
  EXPECT_TRUE(automatic.eigenvalues == dense.eigenvalues);
  EXPECT_EQ(automatic.operator_applications, 0);
}

// block_size 0: the block size comes from the words an application streams
// and is reported. Small pencils, whose factor and basis stay in cache, keep
// the single vector; a 250 x 250 grid Laplacian (62,500 DOFs: its basis
// alone streams 2.5M words per application) takes the block. Checked
// against the dense oracle and the grid's closed form.
TEST(LanczosAutomatic, BlockSizeFromTheWordsAnApplicationStreams) {
  struct Case {
    const char* name;
    Pencil pencil;
    int count;
    int expected_block;
  };
  const Case cases[] = {{"chain", testing::spring_chain(600, 1.0, 1.0, false), 8, 1},
                        {"random", testing::random_pencil(300, 41, false), 12, 1},
                        {"grid", testing::grid_laplacian(250, 250), 20, kAutomaticBlock}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    EigenOptions o;
    o.count = c.count;
    o.method = EigenMethod::lanczos;
    ASSERT_EQ(o.block_size, 0);
    const double shift = default_shift(c.pencil.K, c.pencil.M);
    SparseCholesky factor;
    ASSERT_TRUE(factor.factorize_shifted(c.pencil.K, c.pencil.M, shift).ok);
    const Index n = c.pencil.K.rows();
    EXPECT_EQ(automatic_block_size(n, factor.statistics().factor_nnz, c.count), c.expected_block)
        << "words per application " << application_words(n, factor.statistics().factor_nnz, c.count);
    const EigenResult r = solve_lanczos(c.pencil.K, c.pencil.M, o);
    EXPECT_EQ(r.block_size, c.expected_block);
    if (n <= 600) {
      expect_matches_oracle(c.pencil, r, oracle(c.pencil, c.count, shift), c.count, 0.0);
    } else {
      expect_grid_modes(c.pencil, r, 250, 250, c.count);
    }
  }
}

TEST(LanczosAutomatic, BlockSizeFitsAGivenSubspace) {
  // The grid takes the block (test above) when the subspace is free; a
  // given one needs room for two blocks beyond the 20 wanted pairs, and the
  // block iteration converges in the tightest basis that leaves it.
  const Pencil p = testing::grid_laplacian(250, 250);
  SparseCholesky factor;
  ASSERT_TRUE(factor.factorize_shifted(p.K, p.M, default_shift(p.K, p.M)).ok);
  const double nnz = factor.statistics().factor_nnz;
  EigenOptions o;
  o.count = 20;
  o.method = EigenMethod::lanczos;
  o.subspace = 20 + 2 * kAutomaticBlock - 1;
  EXPECT_EQ(o.resolved_block(p.K.rows(), nnz), 1);
  o.subspace = 20 + 2 * kAutomaticBlock;
  EXPECT_EQ(o.resolved_block(p.K.rows(), nnz), kAutomaticBlock);
  const EigenResult r = solve_lanczos(p.K, p.M, o);
  EXPECT_EQ(r.block_size, kAutomaticBlock);
  expect_grid_modes(p, r, 250, 250, 20);
}

}  // namespace
}  // namespace rigflex::linalg
