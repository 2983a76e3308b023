// The dense solver is the oracle of the Lanczos tests; here it is itself
// checked against closed forms and against Eigen's generalized solver.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "linalg/eigen_solver.hpp"
#include "test_pencils.hpp"

namespace rigflex::linalg {
namespace {

using testing::Pencil;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// Eight masses m = 10 between springs k = 1e5, fixed at both ends:
// f_n = (1/pi) sqrt(k/m) sin(n pi / 18).
VectorXd chain_frequencies(int count) {
  VectorXd f(count);
  for (int j = 1; j <= count; ++j) {
    f[j - 1] = std::sqrt(1e5 / 10.0) * std::sin(j * std::numbers::pi / 18.0) / std::numbers::pi;
  }
  return f;
}

TEST(DenseEigen, EightMassChainMatchesClosedForm) {
  const Pencil p = testing::spring_chain(8, 1e5, 10.0, false);
  const EigenResult r = solve_dense(MatrixXd(p.K), MatrixXd(p.M), 8, -1.0);
  ASSERT_TRUE(r.converged) << r.message;
  // cond(K) = 32: eigenvalues come out to a few eps; 1e-10 is the brief's bar.
  testing::expect_same_eigenvalues(r.frequencies_hz(), chain_frequencies(8), 1e-10, 0.0);
  // Residuals of a backward-stable dense solve are O(eps) relative.
  testing::expect_valid_pairs(p, r, 1e-12, 1e-12);
}

TEST(DenseEigen, MatchesEigenGeneralizedSolverForDefiniteMass) {
  const Pencil p = testing::random_pencil(150, 31, false);
  const EigenResult r = solve_dense(MatrixXd(p.K), MatrixXd(p.M), 25, -0.01);
  ASSERT_TRUE(r.converged) << r.message;
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> reference{MatrixXd(p.K), MatrixXd(p.M)};
  // Both are backward stable: |d lambda| <= eps ||K|| cond(M) ~ 1e-16 * 20 * 4
  // against lambda >= 0.025, i.e. < 1e-12 relative.
  testing::expect_same_eigenvalues(r.eigenvalues, reference.eigenvalues().head(25), 1e-11, 0.0);
  testing::expect_valid_pairs(p, r, 1e-12, 1e-12);
}

TEST(DenseEigen, SingularMassMatchesStaticCondensation) {
  // With a diagonal M, condensing the massless DOFs out statically is exact:
  // K_r = K_mm - K_ms K_ss^-1 K_sm, M_r = M_mm. An independent reference.
  const Pencil p = testing::random_pencil(120, 13, true);
  const MatrixXd K(p.K), M(p.M);
  std::vector<Index> massed, massless;
  for (Index i = 0; i < 120; ++i) (M(i, i) > 0.0 ? massed : massless).push_back(i);
  const MatrixXd Kmm = K(massed, massed), Kms = K(massed, massless), Kss = K(massless, massless);
  const MatrixXd Kr = Kmm - Kms * Kss.llt().solve(Kms.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> reference(Kr, M(massed, massed));

  const EigenResult r = solve_dense(K, M, 30, -0.01);
  ASSERT_TRUE(r.converged) << r.message;
  // cond(K_ss) ~ 1e2 adds to the condensation's rounding: 1e-10 relative.
  testing::expect_same_eigenvalues(r.eigenvalues, reference.eigenvalues().head(30), 1e-10, 0.0);
  testing::expect_valid_pairs(p, r, 1e-10, 1e-12);
}

TEST(DenseEigen, NeverReturnsInfiniteEigenvalues) {
  const Pencil p = testing::random_pencil(60, 17, true);  // 20 massless DOFs
  const EigenResult r = solve_dense(MatrixXd(p.K), MatrixXd(p.M), 60, -0.01);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.converged_count, 40);
  EXPECT_EQ(r.eigenvalues.size(), 40);
  testing::expect_valid_pairs(p, r, 1e-10, 1e-12);
}

TEST(DenseEigen, ShiftAboveLowestEigenvalueIsReported) {
  const Pencil p = testing::spring_chain(8, 1e5, 10.0, false);
  const EigenResult r = solve_dense(MatrixXd(p.K), MatrixXd(p.M), 3, 1e4);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("not positive definite"), std::string::npos) << r.message;
  EXPECT_TRUE(r.mechanism_dofs.empty());
}

TEST(DenseEigen, InvalidArgumentsThrow) {
  const MatrixXd I = MatrixXd::Identity(4, 4);
  EXPECT_THROW(solve_dense(I, MatrixXd::Identity(3, 3), 1, -1.0), std::invalid_argument);
  EXPECT_THROW(solve_dense(I, I, 0, -1.0), std::invalid_argument);
  EXPECT_THROW(solve_dense(I, I, 5, -1.0), std::invalid_argument);
  EXPECT_THROW(solve_dense(I, I, 1, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex::linalg
