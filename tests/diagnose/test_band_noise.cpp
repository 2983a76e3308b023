// The swing band's noise measured just above the band
// (diagnose/band_noise.hpp), against synthetic channels whose noise is known:
// white, white under a swing and a frame's ringing line, and coloured by a
// first-order low-pass. Records of 60 s at 500 Hz for a swing of 0.583 Hz
// (the trifilar's): the near-band estimate is then the median over 27 bins
// of a Welch spectrum averaged over 26 half-overlapping segments, within
// about 3 % (one standard deviation, in sigma) of the noise's level; the
// tolerances below are 3 of those, widened where a line biases the median
// (stated there).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "diagnose/band_noise.hpp"
#include "diagnose/history_comparison.hpp"

namespace {

using namespace rigflex;

constexpr double kStep = 0.002, kSwingHz = 0.583;

Eigen::VectorXd white(Eigen::Index n, double sigma, std::mt19937_64& rng) {
  std::normal_distribution<double> w(0.0, sigma);
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k) x(k) = w(rng);
  return x;
}

Eigen::VectorXd tone(Eigen::Index n, double amplitude, double hz, double decay_per_s = 0.0) {
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * kStep;
    x(k) = amplitude * std::exp(-decay_per_s * t) * std::sin(2.0 * std::numbers::pi * hz * t + 0.3);
  }
  return x;
}

TEST(BandNoise, WhiteNoiseUnderASwingAndARingingLineIsMeasuredAsWhite) {
  const Eigen::Index n = 30000;
  std::mt19937_64 rng(7);
  Eigen::MatrixXd x(n, 3);
  x.col(0) = white(n, 1.0, rng);
  // An encoder: 0.05 rad of swing, 0.03 rad of a second swing mode decaying, 2e-5 rad of noise (93 dB below).
  x.col(1) = tone(n, 0.05, 0.55) + tone(n, 0.03, kSwingHz, 0.02) + white(n, 2e-5, rng);
  // A load cell with a frame mode ringing at 4 Hz, 5 x the noise.
  x.col(2) = tone(n, 5.0, 4.0) + white(n, 1.0, rng) + Eigen::VectorXd::Constant(n, 600.0);
  const diagnose::SwingBand band = diagnose::swing_band(kStep, kSwingHz);
  const Eigen::VectorXd near = diagnose::near_band_noise(x, band);
  const Eigen::VectorXd third = diagnose::channel_noise(x);
  EXPECT_NEAR(near(0), 1.0, 0.1);
  EXPECT_NEAR(near(1) / 2e-5, 1.0, 0.1);  // the swing does not leak into the near band
  // The line raises the bins of Hann's main lobe and first sidelobes, a
  // few of the near band's 27: the median moves up the noise bins'
  // distribution by their share (bounded here at +20 % in sigma).
  EXPECT_GT(near(2), 0.9);
  EXPECT_LT(near(2), 1.2);
  // White noise keeps the third differences' estimate, to the last bit.
  const Eigen::VectorXd used = diagnose::band_noise(third, near);
  for (Eigen::Index c = 0; c < 3; ++c) EXPECT_EQ(used(c), third(c)) << c;
}

TEST(BandNoise, NoiseThroughALowPassIsWeighedByItsLevelInTheBand) {
  const Eigen::Index n = 30000;
  std::mt19937_64 rng(11);
  const double corner_hz = 30.0, a = std::exp(-2.0 * std::numbers::pi * corner_hz * kStep);
  Eigen::MatrixXd x(n, 1);
  const Eigen::VectorXd w = white(n, std::sqrt(1.0 - a * a), rng);
  double e = 0;
  for (Eigen::Index k = 0; k < n; ++k) x(k, 0) = e = a * e + w(k);
  x.col(0) += tone(n, 300.0, kSwingHz);
  // White noise of the same spectral density at low frequencies (the RMS is 1).
  const double in_band = std::sqrt((1.0 + a) / (1.0 - a));
  const diagnose::SwingBand band = diagnose::swing_band(kStep, kSwingHz);
  const Eigen::VectorXd near = diagnose::near_band_noise(x, band);
  const Eigen::VectorXd third = diagnose::channel_noise(x);
  EXPECT_LT(third(0), 0.3 * in_band);  // a fifth: what the fits weighed by before
  // The low-pass's slope over the near band (to 8.75 Hz: -4 % in density at its top) lowers it a little.
  EXPECT_NEAR(near(0) / in_band, 1.0, 0.1);
  const Eigen::VectorXd used = diagnose::band_noise(third, near);
  EXPECT_DOUBLE_EQ(used(0), near(0) / diagnose::kColouredNoiseMargin);
}

TEST(BandNoise, ARecordTooShortForTheEstimateKeepsTheThirdDifferences) {
  std::mt19937_64 rng(3);
  Eigen::MatrixXd x(2000, 1);  // 4 s: the band's filter takes 3.6 s of it
  x.col(0) = white(2000, 1.0, rng);
  const diagnose::SwingBand band = diagnose::swing_band(kStep, kSwingHz);
  const Eigen::VectorXd near = diagnose::near_band_noise(x, band);
  EXPECT_EQ(near(0), 0.0);
  const Eigen::VectorXd third = diagnose::channel_noise(x);
  EXPECT_EQ(diagnose::band_noise(third, near)(0), third(0));
}

}  // namespace
