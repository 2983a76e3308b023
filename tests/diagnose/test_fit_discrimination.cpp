// Vuong's test of two non-nested fits (diagnose/fit_discrimination.hpp):
// its size on two fits equally far from the truth (one noise record,
// correlated in time as the swing band's is), its power on a fit with a
// systematic error and on a large misfit that few rows carry, the Schwarz
// penalty, and its refusal of residuals that do not match the rows.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "diagnose/fit_discrimination.hpp"

namespace rigflex {
namespace {

constexpr int kHistories = 12, kChannels = 5, kRows = 60;
// A moving average of four white samples has autocorrelations 3/4, 1/2,
// 1/4: a sum's variance is 4 x its samples', one independent in four.
constexpr double kIndependence = 0.25;

using Residuals = std::vector<Eigen::VectorXd>;

// Unit-variance noise, a moving average of four white samples (scaled), per
// history stacked channel by channel.
Residuals correlated_noise(std::mt19937& rng, int histories = kHistories) {
  std::normal_distribution<double> n01;
  Residuals out;
  for (int j = 0; j < histories; ++j) {
    Eigen::VectorXd r(kChannels * kRows);
    for (int c = 0; c < kChannels; ++c) {
      double w[4] = {n01(rng), n01(rng), n01(rng), n01(rng)};
      for (int k = 0; k < kRows; ++k) {
        r(c * kRows + k) = 0.5 * (w[0] + w[1] + w[2] + w[3]);
        w[k % 4] = n01(rng);
      }
    }
    out.push_back(r);
  }
  return out;
}

// noise + amplitude x f(row, channel, history), per history.
template <class F>
Residuals plus(const Residuals& noise, double amplitude, F f) {
  Residuals out = noise;
  for (size_t j = 0; j < out.size(); ++j) {
    for (int c = 0; c < kChannels; ++c) {
      for (int k = 0; k < kRows; ++k) out[j](c * kRows + k) += amplitude * f(k, c, static_cast<int>(j));
    }
  }
  return out;
}

diagnose::DiscriminationInput input(const Residuals& a, const Residuals& b, double independence = kIndependence) {
  diagnose::DiscriminationInput in;
  in.first = &a;
  in.second = &b;
  in.rows.assign(a.size(), kRows);
  in.independence = independence;
  return in;
}

TEST(FitDiscrimination, IdenticalFitsCannotBeToldApart) {
  std::mt19937 rng(1);
  const auto r = correlated_noise(rng);
  const auto d = diagnose::discriminate(input(r, r));
  EXPECT_EQ(d.log_likelihood_ratio, 0.0);
  EXPECT_EQ(d.p_value, 1.0);
}

// Rejections at the 5 % level among 400 pairs of fits to one noise record,
// each fit off the truth by a systematic error of its own with the same
// energy (sine against cosine over three whole periods, 0.3 x the noise,
// random phases): the two are equally good.
int rejections_of_equal_fits(double independence) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi);
  const double w = 2 * std::numbers::pi / 20;  // 60 rows: three periods
  int rejected = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const auto noise = correlated_noise(rng);
    std::vector<double> phi(kChannels * kHistories);
    for (auto& p : phi) p = phase(rng);
    const auto a = plus(noise, 0.3, [&](int k, int c, int j) { return std::sin(w * k + phi[j * kChannels + c]); });
    const auto b = plus(noise, 0.3, [&](int k, int c, int j) { return std::cos(w * k + phi[j * kChannels + c]); });
    if (diagnose::discriminate(input(a, b, independence)).p_value < 0.05) ++rejected;
  }
  return rejected;
}

// About 5 % of equally good pairs are told apart: the bounds hold 400 draws
// of a binomial(400, 0.05) (mean 20, sd 4.4) with probability above 0.997.
// Taken as independent, the correlated samples would be told apart far
// more often. Measured: 11 of 400 (the better fit's own 0.3 x the noise
// counts as noise: slightly conservative), 101 of 400 taken as independent.
TEST(FitDiscrimination, EquallyGoodFitsAreToldApartAtTheTestsLevel) {
  const int rejected = rejections_of_equal_fits(kIndependence);
  EXPECT_GE(rejected, 8);
  EXPECT_LE(rejected, 34);
  EXPECT_GT(rejections_of_equal_fits(1.0), 60);
}

// A fit that misses by a systematic error of 0.6 x the noise (a slow sine,
// as a missing effect leaves) against one at the noise: over 3600 samples
// the ratio's mean is 0.6^2 / 4 per sample, 324 in all, against a standard
// error of sqrt(0.36 x 1800 x 4) = 51: z near 6.
TEST(FitDiscrimination, ASystematicErrorIsToldApartFromTheNoise) {
  std::mt19937 rng(3);
  const auto good = correlated_noise(rng);
  const auto bad = plus(good, 0.6, [](int k, int c, int j) { return std::sin(0.4 * k + c + j); });
  const auto d = diagnose::discriminate(input(good, bad));
  EXPECT_GT(d.log_likelihood_ratio, 0.0);
  EXPECT_GT(d.z, 4.0);
  EXPECT_LT(d.p_value, 1e-4);
  const auto reversed = diagnose::discriminate(input(bad, good));
  EXPECT_NEAR(reversed.z, -d.z, 1e-12);
}

// A fit at the noise against one that misses by up to 10 x the noise,
// decaying over the first rows as a swing's misfit does, on three records:
// however unevenly the rows carry the difference, it is told (the ratio's
// spread over the rows, Vuong's own variance, would count that unevenness
// as noise).
TEST(FitDiscrimination, AnUnevenLargeMisfitIsToldApartOnShortRecords) {
  std::mt19937 rng(13);
  const auto good = correlated_noise(rng, 3);
  const auto bad = plus(good, 10.0, [](int k, int c, int j) { return std::exp(-k / 5.0) * std::sin(0.4 * k + c + j); });
  EXPECT_LT(diagnose::discriminate(input(good, bad)).p_value, 1e-6);
}

// Schwarz's penalty, (p1 - p2) / 2 ln(n) off the ratio of the richer fit,
// is reported but leaves the test alone: a fit with two more parameters
// that differs from the other by a hair (1e-4 x the noise) is not told
// apart by the penalty over a vanishing standard error.
TEST(FitDiscrimination, TheRicherFitsPenaltyIsReportedNotTested) {
  std::mt19937 rng(5);
  const auto a = correlated_noise(rng);
  const auto b = plus(a, 1e-4, [](int k, int c, int j) { return std::sin(0.4 * k + c + j); });
  auto in = input(a, b);
  const auto plain = diagnose::discriminate(in);
  in.parameter_difference = 2;
  const auto charged = diagnose::discriminate(in);
  const double n = kHistories * kChannels * kRows * kIndependence;
  EXPECT_NEAR(charged.penalized, plain.log_likelihood_ratio - std::log(n), 1e-9);
  EXPECT_EQ(charged.z, plain.z);
  EXPECT_GT(charged.p_value, 0.01);
}

TEST(FitDiscrimination, ResidualsThatDoNotMatchTheRowsAreRefused) {
  std::mt19937 rng(9);
  const auto a = correlated_noise(rng);
  auto b = a;
  b[4].conservativeResize(b[4].size() - 1);
  EXPECT_THROW(diagnose::discriminate(input(a, b)), std::invalid_argument);
  auto in = input(a, a);
  in.rows[2] = 7;  // 300 values are not whole rows of 7
  EXPECT_THROW(diagnose::discriminate(in), std::invalid_argument);
  EXPECT_THROW(diagnose::discriminate(input(a, a, 0.0)), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex
