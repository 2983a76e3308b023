// Encoder convention of shared/spec/rig-conventions.md: hand-worked cases and
// the round trip direction -> angles -> direction.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "rig/encoder.hpp"

using namespace rigflex::rig;
using Eigen::Vector3d;

TEST(Encoder, HandWorkedDirections) {
  const Vector3d a(1, 0, 0);  // b = z x a = y
  // alpha = 90 deg about x swings -z onto +y.
  EXPECT_LT((rod_direction(a, {std::numbers::pi / 2, 0.0}) - Vector3d(0, 1, 0)).norm(), 1e-15);
  // beta = 30 deg about y swings -z towards -x: u = -a sin(beta) - z cos(beta).
  EXPECT_LT((rod_direction(a, {0.0, std::numbers::pi / 6}) - Vector3d(-0.5, 0, -std::sqrt(3.0) / 2)).norm(), 1e-15);
  // A rod leaning towards +y from an axis along +y: a = y, b = z x y = -x; beta > 0 moves u to -a.
  const EncoderAngles e = encoder_angles(Vector3d(0, 1, 0), Vector3d(0, -0.1, -1).normalized());
  EXPECT_NEAR(e.alpha, 0.0, 1e-15);
  EXPECT_NEAR(e.beta, std::asin(0.1 / std::sqrt(1.01)), 1e-15);
  // Hanging vertically: both zero.
  const EncoderAngles zero = encoder_angles(Vector3d(std::sqrt(0.5), std::sqrt(0.5), 0), Vector3d(0, 0, -1));
  EXPECT_EQ(zero.alpha, 0.0);
  EXPECT_EQ(zero.beta, 0.0);
}

TEST(Encoder, RoundTripDirectionAnglesDirection) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double worst = 0;
  for (int k = 0; k < 1000; ++k) {
    const double phi = std::numbers::pi * U(gen);
    const Vector3d a(std::cos(phi), std::sin(phi), 0);
    const EncoderAngles in{0.6 * U(gen), 0.6 * U(gen)};
    const Vector3d u = rod_direction(a, in);
    const EncoderAngles out = encoder_angles(a, u);
    worst = std::max({worst, std::abs(out.alpha - in.alpha), std::abs(out.beta - in.beta),
                      (rod_direction(a, out) - u).norm()});
  }
  EXPECT_LT(worst, 1e-14);  // a few rounding errors of asin/atan2
}
