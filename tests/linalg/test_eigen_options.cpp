#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "linalg/eigen_solver.hpp"
#include "test_pencils.hpp"

namespace rigflex::linalg {
namespace {

// Expects validate(n) to throw std::invalid_argument naming `option`.
void expect_rejected(const EigenOptions& o, Eigen::Index n, const std::string& option) {
  try {
    o.validate(n);
    ADD_FAILURE() << "no exception for " << option;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
  }
}

TEST(EigenOptions, DefaultsAreValid) { EXPECT_NO_THROW(EigenOptions{}.validate(100)); }

TEST(EigenOptions, InvalidValuesThrowNamingTheOption) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with = [](auto change) {
    EigenOptions o;
    change(o);
    return o;
  };
  expect_rejected(with([](EigenOptions& o) { o.count = 0; }), 100, "count");
  expect_rejected(with([](EigenOptions& o) { o.count = 101; }), 100, "count");
  expect_rejected(with([](EigenOptions& o) { o.tolerance = 0.0; }), 100, "tolerance");
  expect_rejected(with([](EigenOptions& o) { o.tolerance = -1e-8; }), 100, "tolerance");
  expect_rejected(with([&](EigenOptions& o) { o.tolerance = nan; }), 100, "tolerance");
  expect_rejected(with([](EigenOptions& o) { o.tolerance = 1.0; }), 100, "tolerance");
  expect_rejected(with([&](EigenOptions& o) { o.shift = inf; }), 100, "shift");
  expect_rejected(with([](EigenOptions& o) { o.block_size = -1; }), 100, "block_size");
  expect_rejected(with([](EigenOptions& o) { o.block_size = 101; }), 100, "block_size");
  expect_rejected(with([](EigenOptions& o) { o.subspace = 10; }), 100, "subspace");
  expect_rejected(with([](EigenOptions& o) { o.max_restarts = -1; }), 100, "max_restarts");
  expect_rejected(with([](EigenOptions& o) { o.dense_threshold = -1; }), 100, "dense_threshold");
  expect_rejected(EigenOptions{}, 0, "DOFs");
}

TEST(EigenOptions, SolversValidateBeforeWorking) {
  const testing::Pencil p = testing::random_pencil(50, 1, false);
  EigenOptions o;
  o.count = 51;
  EXPECT_THROW(solve_lanczos(p.K, p.M, o), std::invalid_argument);
  o.count = 3;
  EXPECT_THROW(solve_lanczos(p.K, SpMat(49, 49), o), std::invalid_argument);
}

TEST(EigenOptions, ResolvedSubspace) {
  EigenOptions o;
  EXPECT_EQ(o.resolved_subspace(1000, 1), 30);  // max(2 * 10, 10 + 20)
  EXPECT_EQ(o.resolved_subspace(25, 1), 25);    // capped at n
  o.count = 8;
  EXPECT_EQ(o.resolved_subspace(8, 4), 12);  // room for count + one block
  o.count = 20;
  EXPECT_EQ(o.resolved_subspace(1000, 12), 44);  // count + 2 blocks
  o.subspace = 40;
  EXPECT_EQ(o.resolved_subspace(8, 4), 40);
}

TEST(EigenOptions, AutomaticBlockSizeFollowsTheWordsAnApplicationStreams) {
  EXPECT_EQ(EigenOptions{}.block_size, 0);  // automatic by default
  // count 20: basis 40, so an application streams nnz(L) + 40 n words.
  const Eigen::Index n = 50000;
  EXPECT_DOUBLE_EQ(application_words(n, 1e6, 20), 1e6 + 40.0 * n);
  const double threshold_nnz = kAutomaticBlockWords - 40.0 * n;
  EXPECT_EQ(automatic_block_size(n, 0.99 * threshold_nnz, 20), 1);
  EXPECT_EQ(automatic_block_size(n, 1.01 * threshold_nnz, 20), kAutomaticBlock);
  // A large basis alone is enough: a banded model of 100k DOFs.
  EXPECT_EQ(automatic_block_size(100000, 5.0 * 100000, 20), kAutomaticBlock);
  // Tiny problems keep the single vector whatever their fill.
  EXPECT_EQ(automatic_block_size(20, 20.0 * 20, 3), 1);
}

TEST(EigenResult, FrequenciesInHertz) {
  EigenResult r;
  const double omega = 2.0 * std::numbers::pi * 5.0;
  r.eigenvalues = Eigen::Vector3d(-1e-12, omega * omega, 4.0 * omega * omega);
  const Eigen::VectorXd f = r.frequencies_hz();
  EXPECT_EQ(f[0], 0.0);
  EXPECT_NEAR(f[1], 5.0, 1e-14);
  EXPECT_NEAR(f[2], 10.0, 1e-14);
}

}  // namespace
}  // namespace rigflex::linalg
