// diagnose/period_allowance: what a simulator's period error leaves in the
// swing band, against the closed form for one sinusoid.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "diagnose/period_allowance.hpp"

namespace rigflex::diagnose {
namespace {

// A 15 s record at 500 Hz of A sin(omega t) on one channel of unit weight.
BandTarget sinusoid_target(double amplitude, double hz) {
  BandTarget b;
  const double h = 0.002;
  const Eigen::Index n = 7501;
  b.record.step_s = h;
  b.record.t = Eigen::VectorXd::LinSpaced(n, 0.0, h * static_cast<double>(n - 1));
  b.record.channels = (2 * std::numbers::pi * hz * b.record.t).array().sin().matrix() * amplitude;
  b.band = swing_band(h, hz);
  b.at = band_samples(b.band, n);
  b.measured = band_filter(b.band, b.record.channels, b.at);
  b.weight = Eigen::VectorXd::Ones(1);
  return b;
}

// eps (t - t0) omega A cos(omega t) less its projection on cos(omega t):
// sum eps^2 omega^2 A^2 cos^2 (t - tbar)^2 -> eps^2 omega^2 A^2 N / 2 x the
// variance of the band samples' times, T^2 / 12 (cos^2 averages to 1/2 over
// the ~9 periods; its beat with (t - tbar)^2 and the one-sided derivative,
// omega h / 2 = 0.2 %, keep the ratio within 3 %).
TEST(PeriodAllowance, ASinusoidsDriftMatchesTheClosedForm) {
  const double A = 80.0, hz = 0.6, eps = 1.5e-5;
  const BandTarget b = sinusoid_target(A, hz);
  const double N = static_cast<double>(b.at.size());
  const double T = b.record.t(b.at.back()) - b.record.t(b.at.front());
  const double omega = 2 * std::numbers::pi * hz;
  const double expected = eps * eps * omega * omega * A * A * N / 2 * T * T / 12;
  const double got = period_error_residual({&b}, eps);
  EXPECT_NEAR(got / expected, 1.0, 0.03) << got << " vs " << expected;
  // Square law in eps, and the band's weight enters squared.
  EXPECT_NEAR(period_error_residual({&b}, 2 * eps) / got, 4.0, 1e-9);
  BandTarget quiet = b;
  quiet.weight(0) = 3.0;
  EXPECT_NEAR(period_error_residual({&quiet}, eps) / got, 9.0, 1e-9);
  // Two records add.
  EXPECT_NEAR(period_error_residual({&b, &quiet}, eps) / got, 10.0, 1e-9);
}

TEST(PeriodAllowance, NoPeriodErrorLeavesNothingAndANegativeOneIsRefused) {
  const BandTarget b = sinusoid_target(10.0, 0.8);
  EXPECT_EQ(period_error_residual({&b}, 0.0), 0.0);
  EXPECT_THROW(period_error_residual({&b}, -1e-6), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex::diagnose
