// Lanczos runs that stop short: the cause named from the Ritz values, the
// remedy said, and the automatic retry where it is safe.
//
// The end-to-end case is a diagonal pencil (M = I) whose spectrum is known
// exactly: 10 separated eigenvalues, then 700 spread evenly over 1 % at
// 1e4 (rad/s)^2 (15.92 Hz), like the spurious drilling band of a thick shell
// plate that sits among the wanted modes, then the rest up to 2e8. The
// default Lanczos (basis 40, 200 restarts) converges 10 of the 20 wanted
// pairs there; four times the basis converges all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "linalg/eigen_solver.hpp"
#include "linalg/lanczos_stall.hpp"
#include "test_pencils.hpp"

namespace rigflex::linalg {
namespace {

using Eigen::Index;
using Eigen::VectorXd;

constexpr Index kSize = 3000;
constexpr int kCluster = 700;
constexpr double kClusterLambda = 1e4;
// The pairs a converged run returns are checked as in test_lanczos.cpp:
// residual 1e-8 and M-orthonormality 1e-10 from the convergence tolerance
// 1e-10; eigenvalues against the exact diagonal within 1e-9 relative.
constexpr double kStallResidual = 1e-8;
constexpr double kStallOrthogonality = 1e-10;
constexpr double kStallEigenvalue = 1e-9;

VectorXd clustered_spectrum() {
  VectorXd d(kSize);
  for (Index i = 0; i < 10; ++i) d[i] = 100.0 * static_cast<double>((i + 1) * (i + 1));
  for (Index i = 0; i < kCluster; ++i) d[10 + i] = kClusterLambda * (1.0 + 1e-2 * static_cast<double>(i) / kCluster);
  for (Index i = 10 + kCluster; i < kSize; ++i) {
    d[i] = 2.0 * kClusterLambda * std::pow(1e4, static_cast<double>(i - 10 - kCluster) / kSize);
  }
  return d;
}

testing::Pencil clustered_pencil() {
  return {testing::diagonal_matrix(clustered_spectrum()), testing::diagonal_matrix(VectorXd::Ones(kSize))};
}

EigenOptions wanted_20(bool retry) {
  EigenOptions o;
  o.count = 20;
  o.automatic_retry = retry;
  return o;
}

double stall_hz(double lambda) { return std::sqrt(lambda) / (2.0 * std::numbers::pi); }

TEST(LanczosStall, AClusterIsNamedWithItsFrequencyAndTheRemedy) {
  const testing::Pencil p = clustered_pencil();
  const EigenResult r = solve_lanczos(p.K, p.M, wanted_20(false));
  ASSERT_FALSE(r.converged);
  EXPECT_EQ(r.retries, 0);
  EXPECT_EQ(r.stall.cause, StallCause::clustered) << r.message;
  // The estimates sit inside the cluster's 1 % band.
  EXPECT_GE(r.stall.cluster_hz, stall_hz(kClusterLambda));
  EXPECT_LE(r.stall.cluster_hz, stall_hz(kClusterLambda * 1.01));
  EXPECT_GE(r.stall.cluster_size, kClusterMembers);
  EXPECT_NE(r.message.find("not converged"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find(r.stall.why), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("enlarge the basis"), std::string::npos) << r.message;
  // The pairs that did converge are still right.
  const VectorXd exact = clustered_spectrum().head(r.converged_count);
  testing::expect_same_eigenvalues(r.eigenvalues, exact, kStallEigenvalue, 0.0);
  testing::expect_valid_pairs(p, r, kStallResidual, kStallOrthogonality);
}

TEST(LanczosStall, TheAutomaticRetryConvergesTheCluster) {
  const testing::Pencil p = clustered_pencil();
  const EigenResult r = solve_lanczos(p.K, p.M, wanted_20(true));
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.retries, 1);
  EXPECT_NE(r.first_attempt.find("within 0.1 %"), std::string::npos) << r.first_attempt;
  EXPECT_EQ(r.stall.cause, StallCause::none);
  testing::expect_same_eigenvalues(r.eigenvalues, clustered_spectrum().head(20), kStallEigenvalue, 0.0);
  testing::expect_valid_pairs(p, r, kStallResidual, kStallOrthogonality);
}

TEST(LanczosStall, TheRetryOnAGivenFactorConvergesToo) {
  const testing::Pencil p = clustered_pencil();
  SparseCholesky factor;
  const PencilFactorization pencil = factorize_pencil(p.K, p.M, std::nullopt, factor);
  ASSERT_TRUE(pencil.ok) << pencil.message;
  const EigenResult r = solve_lanczos(p.K, p.M, wanted_20(true), factor);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.retries, 1);
  testing::expect_same_eigenvalues(r.eigenvalues, clustered_spectrum().head(20), kStallEigenvalue, 0.0);
}

TEST(LanczosStall, NoRetryPastTheMemoryAllowed) {
  const testing::Pencil p = clustered_pencil();
  EigenOptions o = wanted_20(true);
  // The factor (3000 nonzeros) and the default basis fit; four times the
  // basis, 3000 x 168 doubles = 4 MB, does not.
  o.max_factor_bytes = 2e6;
  const EigenResult r = solve_lanczos(p.K, p.M, o);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.retries, 0);
  EXPECT_EQ(r.stall.cause, StallCause::clustered);
}

// diagnose_stall on the Ritz values alone.
StallFacts facts_from(const VectorXd& lambda, double shift, int converged) {
  StallFacts f;
  f.shift = shift;
  f.theta = (lambda.array() - shift).inverse().matrix();
  f.residual = 1e-3 * f.theta;
  f.count = static_cast<int>(lambda.size()) - 2;
  f.converged = converged;
  f.basis = 2 * f.count;
  f.scale = 1e6;
  return f;
}

TEST(LanczosStall, MoreZeroEigenvaluesThanRigidBodyModesAreAMechanism) {
  VectorXd lambda = VectorXd::Zero(12);
  for (Index i = 8; i < 12; ++i) lambda[i] = 100.0 * static_cast<double>(i);
  for (Index i = 0; i < 8; ++i) lambda[i] = 1e-12 * static_cast<double>(i);  // rounding around zero
  const EigenStall s = diagnose_stall(facts_from(lambda, -1e-4, 3));
  EXPECT_EQ(s.cause, StallCause::mechanism) << s.why;
  EXPECT_NE(s.why.find("8 eigenvalue estimates are zero"), std::string::npos) << s.why;
}

TEST(LanczosStall, SixZeroEigenvaluesAreAFreeBodyNotAMechanism) {
  VectorXd lambda(12);
  for (Index i = 0; i < 6; ++i) lambda[i] = 1e-12;
  for (Index i = 6; i < 12; ++i) lambda[i] = 100.0 * static_cast<double>(i * i);  // well separated
  const EigenStall s = diagnose_stall(facts_from(lambda, -1e-4, 6));
  EXPECT_EQ(s.cause, StallCause::slow_convergence) << s.why;
  EXPECT_NE(s.why.find("6 of 10 pairs converged"), std::string::npos) << s.why;
  EXPECT_NE(s.why.find("slow convergence"), std::string::npos) << s.why;
}

TEST(LanczosStall, AShiftJustBelowAnEigenvalueIsNamed) {
  VectorXd lambda(8);
  for (Index i = 0; i < 8; ++i) lambda[i] = 1e3 * static_cast<double>((i + 1) * (i + 1));
  const double shift = 1e3 * (1.0 - 1e-12);  // 1e-9 (rad/s)^2 below lambda_1, the range is 3.6e4
  const EigenStall s = diagnose_stall(facts_from(lambda, shift, 0));
  EXPECT_EQ(s.cause, StallCause::near_singular_shift) << s.why;
  EXPECT_NE(s.advice.find("lower the shift"), std::string::npos) << s.advice;
}

TEST(LanczosStall, CloseButResolvedEigenvaluesAreNoCluster) {
  VectorXd lambda(8);
  for (Index i = 0; i < 8; ++i) lambda[i] = 1e3 * (1.0 + 2e-3 * static_cast<double>(i));  // 0.2 % apart
  const EigenStall s = diagnose_stall(facts_from(lambda, -1.0, 2));
  EXPECT_EQ(s.cause, StallCause::slow_convergence) << s.why;
  lambda.tail(6).setConstant(1e3 * 1.01);
  lambda.tail(6) += VectorXd::LinSpaced(6, 0.0, 0.5);  // six within 0.05 %
  const EigenStall c = diagnose_stall(facts_from(lambda, -1.0, 2));
  EXPECT_EQ(c.cause, StallCause::clustered) << c.why;
  EXPECT_EQ(c.cluster_size, 6);
  EXPECT_NEAR(c.cluster_hz, stall_hz(1010.0), 0.01);
}

}  // namespace
}  // namespace rigflex::linalg
