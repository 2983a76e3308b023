// diagnose/welch: the periodogram sums the residual spectra and the
// near-band noise estimate share, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "diagnose/welch.hpp"

namespace rigflex::diagnose {
namespace {

// A sine with k0 whole periods per segment of n: the Hann window puts
// A n / 4 into bin k0 and A n / 8 into each neighbour, per segment; an
// offset added to it is removed with each segment's mean.
TEST(Welch, ASineOnABinCentreAndAnOffset) {
  const int n = 256, k0 = 20;
  const double A = 3.0;
  Eigen::VectorXd x(4 * n);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = 7.5 + A * std::sin(2 * std::numbers::pi * k0 * i / n);
  const WelchSums w = welch_sums(x, n);
  ASSERT_EQ(w.segments, 7);  // 4 n samples, half-overlapping
  EXPECT_NEAR(w.window_power, 3.0 * n / 8.0, 1e-9);
  const double per = w.segments;
  EXPECT_NEAR(w.power(k0) / per, A * A * n * n / 16.0, 1e-9 * A * A * n * n);
  EXPECT_NEAR(w.power(k0 + 1) / per, A * A * n * n / 64.0, 1e-9 * A * A * n * n);
  EXPECT_NEAR(w.power(k0 - 1) / per, A * A * n * n / 64.0, 1e-9 * A * A * n * n);
  EXPECT_NEAR(w.power(0), 0.0, 1e-18 * A * A * n * n);       // the offset is gone
  EXPECT_NEAR(w.power(k0 + 5), 0.0, 1e-18 * A * A * n * n);  // Hann leaks to one bin each side only
}

// White noise of variance s^2: each bin's mean is s^2 x window_power. Over
// 511 segments and 119 bins the average's relative scatter is about 0.2 %
// (the half-overlap correlates Hann segments by 17 %); 1 % is 5 of those.
TEST(Welch, WhiteNoiseGivesItsVarianceTimesTheWindowsPower) {
  const int n = 256;
  const double s = 0.4;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0.0, s);
  Eigen::VectorXd x(256 * n);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = g(rng);
  const WelchSums w = welch_sums(x, n);
  ASSERT_EQ(w.segments, 511);
  const double mean = w.power.segment(5, 119).mean() / (w.segments * w.window_power);
  EXPECT_NEAR(mean / (s * s), 1.0, 0.01);
}

TEST(Welch, ARecordShorterThanASegmentHasNoneAndATinySegmentIsRefused) {
  const WelchSums w = welch_sums(Eigen::VectorXd::Ones(100), 128);
  EXPECT_EQ(w.segments, 0);
  EXPECT_EQ(w.power.size(), 65);
  EXPECT_EQ(w.power.squaredNorm(), 0.0);
  EXPECT_THROW(welch_sums(Eigen::VectorXd::Ones(100), 1), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex::diagnose
