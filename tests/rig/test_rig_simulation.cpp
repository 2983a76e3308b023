// Simulated free swings: energy conservation, frequencies against the
// linearization, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rig/effects.hpp"
#include "rig/encoder.hpp"
#include "rig/linearization.hpp"
#include "rig/rig_cases.hpp"
#include "rig/simulation.hpp"

using namespace rigflex;
using rig::Vec3;

namespace {

// Mean frequency from the upward zero crossings of x - mean(x), linearly interpolated.
double crossing_frequency(const Eigen::VectorXd& t, const Eigen::VectorXd& x) {
  const Eigen::VectorXd y = x.array() - x.mean();
  std::vector<double> up;
  for (Eigen::Index k = 1; k < y.size(); ++k) {
    if (y(k - 1) < 0 && y(k) >= 0) up.push_back(t(k - 1) + (t(k) - t(k - 1)) * (-y(k - 1)) / (y(k) - y(k - 1)));
  }
  if (up.size() < 3) return 0.0;
  return (up.size() - 1) / (up.back() - up.front());
}

}  // namespace

TEST(RigSimulation, UndampedEnergyDriftBelowOnePpmOverTwentySeconds) {
  rig::RigModel model = test::multifilar_rig(3, 0.5, 1.4, 900.0, 0.9, 0.35);
  model.body.cog = Vec3(0.05, -0.03, -0.35);
  model.effects.push_back(std::make_shared<rig::RodCompliance>(std::vector<double>(3, 5.0e7)));
  model.simulation.relative_tolerance = 1e-10;
  model.simulation.position_tolerance = 1e-12;
  const rig::RigSystem rig(model);
  const rig::Equilibrium eq = rig::static_equilibrium(rig);
  ASSERT_TRUE(eq.converged) << eq.message;
  const double V0 = rig.potential_energy(eq.configuration);
  rig::Integrator integ(rig, model.simulation);
  rig::InitialCondition ic;
  ic.velocity = Vec3(0.08, -0.05, 0.0);
  ic.angular_velocity = Vec3(0, 0, 0.06);
  rig::Velocity v = rig.at_rest();
  v.V = eq.configuration.q.conjugate() * ic.velocity;
  v.w = eq.configuration.q.conjugate() * ic.angular_velocity;
  integ.reset(0.0, eq.configuration, v);
  const double E0 = rig.kinetic_energy(v) + rig.potential_energy(eq.configuration);
  const double swing = E0 - V0;
  ASSERT_GT(swing, 1.0);
  double worst = 0;
  rig::Configuration c;
  for (int k = 1; k <= 200; ++k) {
    integ.advance_to(0.1 * k);
    integ.state(c, v);
    worst = std::max(worst, std::abs(rig.kinetic_energy(v) + rig.potential_energy(c) - E0));
  }
  EXPECT_LT(worst / swing, 1e-6) << "relative to the swing energy " << swing << " J";
}

TEST(RigSimulation, FreeSwingFrequenciesMatchLinearization) {
  // Body with its CoG 0.6 m below the joints: sway couples with tilt; the
  // simulated yaw and sway periods must agree with the linear modes to 0.5 %.
  rig::RigModel model = test::multifilar_rig(3, 0.6, 1.5, 1200.0, 1.0, 0.6);
  model.effects.push_back(std::make_shared<rig::RodCompliance>(std::vector<double>(3, 8.0e7)));
  const rig::RigSystem rig(model);
  const rig::Linearization lin = rig::linearize(rig);
  rig::HistoryRequest yaw;
  yaw.initial = rig::InitialCondition{0.0, 0.0, 0.004, Vec3::Zero(), Vec3::Zero()};
  yaw.duration_s = 12.0;
  const rig::VirtualHistory h = rig::simulate_history(rig, lin.equilibrium.configuration, yaw);
  // Yaw moves each rod tangentially: the encoder about the radial axis a_i reads it (alpha).
  const double f_yaw = crossing_frequency(h.t, h.alpha.col(0));
  const double f_lin_yaw = test::swing_frequency_along(lin, 5);
  EXPECT_NEAR(f_yaw, f_lin_yaw, 0.005 * f_lin_yaw);
  rig::HistoryRequest sway;
  sway.initial = rig::InitialCondition{0.02, 0.0, 0.0, Vec3::Zero(), Vec3::Zero()};
  sway.duration_s = 12.0;
  const rig::VirtualHistory hs = rig::simulate_history(rig, lin.equilibrium.configuration, sway);
  // The sideways lean of rod 1, rebuilt from its encoders.
  Eigen::VectorXd ux(hs.t.size());
  for (Eigen::Index k = 0; k < hs.t.size(); ++k) {
    const Vec3 u = rig::rod_direction(model.geometry.rods[0].encoder_axis, {hs.alpha(k, 0), hs.beta(k, 0)});
    ux(k) = u.x();
  }
  const double f_x = crossing_frequency(hs.t, ux);
  const double f_lin_sway = test::swing_frequency_along(lin, 0);
  EXPECT_NEAR(f_x, f_lin_sway, 0.005 * f_lin_sway);
}

TEST(RigSimulation, DeterministicForAGivenSeed) {
  rig::RigModel model = test::multifilar_rig(3, 0.5, 1.2, 500.0, 0.8, 0.3);
  model.sensors.force_noise_n = 2.0;
  model.sensors.angle_noise_rad = 1e-4;
  model.sensors.encoder_bits = 16;
  const rig::RigSystem rig(model);
  rig::MeasurementOptions o;
  o.histories = 2;
  o.duration_s = 2.0;
  o.seed = 42;
  const auto a = rig::simulate_measurement(rig, o);
  const auto b = rig::simulate_measurement(rig, o);
  ASSERT_EQ(a[0].size(), 2u);
  EXPECT_EQ(a[0][1].force, b[0][1].force);
  EXPECT_EQ(a[0][1].alpha, b[0][1].alpha);
  o.seed = 43;
  const auto c = rig::simulate_measurement(rig, o);
  EXPECT_NE(a[0][1].force, c[0][1].force);
  // Encoder quantization: every angle is a whole number of 2 pi / 2^16 steps.
  const double step = 2 * std::numbers::pi / 65536.0;
  for (Eigen::Index k = 0; k < a[0][0].alpha.rows(); k += 37) {
    const double counts = a[0][0].alpha(k, 1) / step;
    EXPECT_NEAR(counts, std::round(counts), 1e-6);
  }
  EXPECT_EQ(a[0][0].t.size(), 2 * 500 + 1);
}
