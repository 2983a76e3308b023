// Simulated free swings: energy conservation, frequencies against the
// linearization, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rig/effects.hpp"
#include "rig/encoder.hpp"
#include "rig/generalized_alpha.hpp"
#include "rig/joint_compliance.hpp"
#include "rig/linearization.hpp"
#include "support/rig_cases.hpp"
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
  const rig::Record h = rig::simulate_history(rig, lin.equilibrium.configuration, yaw);
  // Yaw moves each rod tangentially: the encoder about the radial axis a_i reads it (alpha).
  const double f_yaw = crossing_frequency(h.t, h.alpha.col(0));
  const double f_lin_yaw = test::swing_frequency_along(lin, 5);
  EXPECT_NEAR(f_yaw, f_lin_yaw, 0.005 * f_lin_yaw);
  rig::HistoryRequest sway;
  sway.initial = rig::InitialCondition{0.02, 0.0, 0.0, Vec3::Zero(), Vec3::Zero()};
  sway.duration_s = 12.0;
  const rig::Record hs = rig::simulate_history(rig, lin.equilibrium.configuration, sway);
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

TEST(RigSimulation, GeneralizedAlphaMatchesATightBdfRun) {
  // The default integrator against CVODE's BDF2 at 1e-9 / 1e-12 m on a rig
  // with compliant rods (bounce ~9 Hz) and a flexible fixed frame (joint
  // springs): a push, then 8 s of free swing, noise-free.
  rig::RigModel model = test::multifilar_rig(3, 0.6, 1.5, 1200.0, 1.0, 0.6);
  model.effects.push_back(std::make_shared<rig::RodCompliance>(std::vector<double>(3, 8.0e7)));
  rig::FixedFrameModel ff;
  ff.K = 5.0e6 * Eigen::MatrixXd::Identity(9, 9);
  ff.M = 40.0 * Eigen::MatrixXd::Identity(9, 9);
  ff.C = 2.0 * 0.02 * std::sqrt(5.0e6 * 40.0) * Eigen::MatrixXd::Identity(9, 9);
  ff.joint_row = {0, 3, 6};
  ff.source = "test springs";
  model.effects.push_back(std::make_shared<rig::FixedFrameFlexibility>(ff));
  model.sensors.sample_rate_hz = 500.0;
  rig::RigModel reference = model;
  reference.simulation.method = rig::IntegrationMethod::bdf;
  reference.simulation.relative_tolerance = 1e-9;
  reference.simulation.position_tolerance = 1e-12;
  const rig::RigSystem rig(model), ref(reference);
  const rig::Linearization lin = rig::linearize(rig);
  rig::HistoryRequest req;
  req.push = rig::Push{1.0, Vec3(0.3 * 1200.0, 0.2 * 1200.0, 0.0), Vec3(0, 0, 40.0)};
  req.duration_s = 8.0;
  req.linearization = &lin;
  rig::IntegratorStatistics stats;
  const rig::Record a = rig::simulate_history(rig, lin.equilibrium.configuration, req, &stats);
  req.linearization = nullptr;
  const rig::Record b = rig::simulate_history(ref, lin.equilibrium.configuration, req);
  const double h = rig::generalized_alpha_step(lin, 500.0);
  EXPECT_EQ(stats.steps, std::lround(9.0 / h));
  // Bound: generalized-alpha's period error, |dT / T| <= (omega h)^2 / 6 for
  // rho_inf = 0.8 (twice the trapezoidal rule's 1 / 12), turned into a phase
  // drift over the 9 s of the fastest swing, times the amplitude; the same
  // for the forces' swing-induced variation.
  double f_swing = 0;
  for (const auto& m : lin.modes) {
    if (m.kind == rig::RigModeKind::swing) f_swing = std::max(f_swing, m.frequency_hz);
  }
  const double w = 2.0 * std::numbers::pi * f_swing;
  const double phase = w * 9.0 * (w * h) * (w * h) / 6.0;
  const double angle_amplitude = std::max(b.alpha.cwiseAbs().maxCoeff(), b.beta.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd dF = b.force.rowwise() - b.force.colwise().mean();
  const double force_amplitude = dF.cwiseAbs().maxCoeff();
  const double d_angle = std::max((a.alpha - b.alpha).cwiseAbs().maxCoeff(), (a.beta - b.beta).cwiseAbs().maxCoeff());
  const double d_force = (a.force - b.force).cwiseAbs().maxCoeff();
  EXPECT_LT(d_angle, phase * angle_amplitude) << "h " << h << " phase bound " << phase;
  EXPECT_LT(d_force, phase * force_amplitude + 1e-3 * force_amplitude) << "force amplitude " << force_amplitude;
  ::testing::Test::RecordProperty("d_angle_rad", std::to_string(d_angle));
  ::testing::Test::RecordProperty("d_force_n", std::to_string(d_force));
  ::testing::Test::RecordProperty("angle_bound_rad", std::to_string(phase * angle_amplitude));
}

TEST(RigSimulation, GeneralizedAlphaStepResolvesTheFirstDeformationMode) {
  rig::Linearization lin;
  rig::RigMode swing, deformation, high;
  swing.frequency_hz = 0.7;
  deformation.kind = rig::RigModeKind::deformation;
  deformation.frequency_hz = 40.0;
  high.kind = rig::RigModeKind::deformation;
  high.frequency_hz = 900.0;  // above the first deformation mode: damped, not resolved
  lin.modes = {swing, deformation, high};
  const double h = rig::generalized_alpha_step(lin, 500.0);
  EXPECT_NEAR(0.002 / h, std::round(0.002 / h), 1e-12);  // divides the sample interval
  EXPECT_LE(h, 1.0 / (30.0 * 40.0));
  EXPECT_GT(h, 0.5 / (30.0 * 40.0));
  lin.modes = {swing};
  EXPECT_DOUBLE_EQ(rig::generalized_alpha_step(lin, 500.0), 0.002);
  // Records at lower rates: the swing still gets 2 ms (kMaxStep), not the
  // sample interval, whose period error a fit would read as a rod length.
  EXPECT_DOUBLE_EQ(rig::generalized_alpha_step(lin, 100.0), 0.002);
  EXPECT_DOUBLE_EQ(rig::generalized_alpha_step(lin, 125.0), 0.008 / 4.0);
  EXPECT_DOUBLE_EQ(rig::generalized_alpha_step(lin, 300.0), 1.0 / 600.0);
}

TEST(RigSimulation, GeneralizedAlphaResolvesTheRodBounce) {
  // Compliant rods (bounce sqrt(3 k / m) / 2 pi = 25.2 Hz) on a rigid frame:
  // the bounce is the first deformation mode and the default step resolves
  // it; a vertical push excites it, and the load-cell signal's frequency
  // from zero crossings matches the linearization within 0.5 %.
  rig::RigModel model = test::multifilar_rig(3, 0.5, 1.0, 400.0, 0.6, 0.0);
  const double k = std::pow(2.0 * std::numbers::pi * 25.2, 2) * 400.0 / 3.0;
  model.effects.push_back(std::make_shared<rig::RodCompliance>(std::vector<double>(3, k)));
  const rig::RigSystem rig(model);
  const rig::Linearization lin = rig::linearize(rig);
  double f_bounce = 0;
  for (const auto& m : lin.modes) {
    if (m.kind == rig::RigModeKind::deformation) {
      f_bounce = m.frequency_hz;
      break;
    }
  }
  ASSERT_GT(f_bounce, 20.0);
  rig::HistoryRequest req;
  req.push = rig::Push{0.02, Vec3(0, 0, 0.5 * 400.0), Vec3::Zero()};
  req.duration_s = 1.0;
  req.linearization = &lin;
  const rig::Record h = rig::simulate_history(rig, lin.equilibrium.configuration, req);
  Eigen::VectorXd total = h.force.rowwise().sum();
  EXPECT_NEAR(crossing_frequency(h.t, total), f_bounce, 0.005 * f_bounce);
  EXPECT_NEAR(rig::generalized_alpha_step(lin, 500.0, 0.0), 0.002 / std::ceil(0.002 * 30 * f_bounce - 1e-9), 1e-15);
  // simulation.resolve_hz asks for more: 30 steps per period at 100 Hz.
  EXPECT_LE(rig::generalized_alpha_step(lin, 500.0, 100.0), 1.0 / 3000.0);
}

TEST(RigSimulation, RodsBlockStiffnessIsTheRodComplianceEffectsStiffness) {
  // The rig file's nominal rods and the effect build the same rig.
  rig::RigModel plain = test::multifilar_rig(3, 0.5, 1.0, 400.0, 0.6, 0.1);
  rig::RigModel effect = plain;
  plain.rods.stiffness = {3.0e6, 3.2e6, 2.9e6};
  effect.effects.push_back(std::make_shared<rig::RodCompliance>(plain.rods.stiffness));
  const rig::RigSystem a(plain), b(effect);
  EXPECT_FALSE(a.rods_rigid());
  EXPECT_EQ(a.rod_stiffness(), b.rod_stiffness());
  const rig::Linearization la = rig::linearize(a), lb = rig::linearize(b);
  ASSERT_EQ(la.modes.size(), lb.modes.size());
  for (size_t k = 0; k < la.modes.size(); ++k) EXPECT_EQ(la.modes[k].frequency_hz, lb.modes[k].frequency_hz);
  // The effect, where present, replaces the nominal stiffness.
  effect.rods.stiffness = {1e9, 1e9, 1e9};
  EXPECT_EQ(rig::RigSystem(effect).rod_stiffness(), b.rod_stiffness());
}

TEST(RigSimulation, RodDampingDecaysTheBounceAtTheClosedFormRatio) {
  // Three vertical rods on a rigid frame, CoG on the axis: the bounce is a
  // single-DOF oscillator m z'' + (3 c) z' + (3 k) z = 0, damping ratio
  // zeta = 3 c / (2 sqrt(3 k m)). A vertical push excites it; the
  // logarithmic decrement of the load cells' summed force over ten periods
  // gives zeta back. Tolerance 2 %: a tight BDF run (numerical damping
  // below 1e-4 of it) sampled at 200 points per period (peak error 1e-4).
  const double m = 400.0, zeta = 0.02;
  rig::RigModel model = test::multifilar_rig(3, 0.5, 1.0, m, 0.6, 0.0);
  const double k = std::pow(2.0 * std::numbers::pi * 25.2, 2) * m / 3.0;
  const double c = zeta * 2.0 * std::sqrt(3.0 * k * m) / 3.0;
  model.rods.stiffness.assign(3, k);
  model.rods.damping.assign(3, c);
  model.sensors.sample_rate_hz = 5000.0;
  model.simulation.method = rig::IntegrationMethod::bdf;
  model.simulation.relative_tolerance = 1e-10;
  model.simulation.position_tolerance = 1e-13;
  const rig::RigSystem rig(model);
  const rig::Linearization lin = rig::linearize(rig);
  rig::HistoryRequest req;
  req.push = rig::Push{0.01, Vec3(0, 0, 0.5 * m), Vec3::Zero()};
  req.duration_s = 0.6;
  req.linearization = &lin;
  const rig::Record h = rig::simulate_history(rig, lin.equilibrium.configuration, req);
  const Eigen::VectorXd x = h.force.rowwise().sum().array() - m * 9.81;
  std::vector<double> peaks;
  for (Eigen::Index i = 1; i + 1 < x.size(); ++i) {
    if (h.t(i) > 0.05 && x(i) > x(i - 1) && x(i) >= x(i + 1) && x(i) > 0) peaks.push_back(x(i));
  }
  ASSERT_GE(peaks.size(), 11u);
  const double delta = std::log(peaks[0] / peaks[10]) / 10.0;
  const double measured = delta / std::sqrt(4.0 * std::numbers::pi * std::numbers::pi + delta * delta);
  EXPECT_NEAR(measured, zeta, 0.02 * zeta);
  // Without the dampers the same push rings on: the decrement is the solver's only.
  model.rods.damping.clear();
  const rig::RigSystem undamped(model);
  const rig::Record u = rig::simulate_history(undamped, lin.equilibrium.configuration, req);
  const Eigen::VectorXd y = u.force.rowwise().sum().array() - m * 9.81;
  const double first = y.segment(250, 200).maxCoeff(), later = y.tail(200).maxCoeff();
  EXPECT_NEAR(later / first, 1.0, 1e-3);
}

TEST(RigSimulation, GeneralizedAlphaHalvesAStepItsNewtonIterationsCannotTake) {
  // A fixed frame of joint springs (rig/joint_compliance: light joints,
  // 0.07 kg each) under rods that are rigid (axial stiffness ~1e8 N/m),
  // started with the upper joints 10 um off their quasi-static place along
  // each axis (a fitted elastic state, or a frame released deflected): a
  // joint moves by millimetres in the first 2 ms step, beyond what the
  // Newton iterations converge from. The step is taken again in halves; the
  // swing that follows matches a run at a quarter of the step.
  rig::RigModel model = test::noisy_trifilar();
  rig::FixedJointCompliance c;
  c.joints = {Vec3(3.2e-6, 9.1e-6, 1.1e-6), Vec3(6.2e-6, 3.2e-6, 1.1e-6), Vec3(3.2e-6, 6.2e-6, 2.6e-6)};
  c.sway = Eigen::Vector2d(3.0e-6, 1.5e-6);
  model.effects.push_back(
      std::make_shared<rig::FixedFrameFlexibility>(rig::joint_compliance_fixed_frame(model.geometry, 200.0, c)));
  const rig::RigSystem rig(model);
  const rig::Linearization lin = rig::linearize(rig);
  ASSERT_EQ(rig.fixed_dofs(), 9);
  Eigen::VectorXd ds = Eigen::VectorXd::Zero(rig.coordinate_count());
  ds(0) = 0.03;                    // a swing of 30 mm
  ds.tail(9).setConstant(-1e-5);   // every joint 10 um off along each axis
  const rig::Configuration start = rig.displaced(lin.equilibrium.configuration, ds);
  const double h = rig::generalized_alpha_step(lin, 500.0);
  rig::GeneralizedAlpha coarse(rig, lin, h, 1e-10), fine(rig, lin, 0.25 * h, 1e-10);
  coarse.reset(0.0, start, rig.at_rest());
  fine.reset(0.0, start, rig.at_rest());
  coarse.advance_to(1.0);
  fine.advance_to(1.0);
  EXPECT_GT(coarse.statistics().halvings, 0);  // the case needs halving: without it the first step throws
  rig::Configuration a, b;
  rig::Velocity va, vb;
  coarse.state(a, va);
  fine.state(b, vb);
  // Bound: the two step sizes dissipate the joints' start-up vibration
  // differently, and at most its energy reaches the swing. Energy in the
  // swing amplitude A goes as A^2, so the swing's position can differ by
  // A E_joints / E_swing at most (both energies from the linearization's K).
  Eigen::VectorXd joints = Eigen::VectorXd::Zero(ds.size()), swing = joints;
  joints.tail(9) = ds.tail(9);
  swing(0) = ds(0);
  const double e_joints = 0.5 * joints.dot(lin.K * joints), e_swing = 0.5 * swing.dot(lin.K * swing);
  const double bound = ds(0) * e_joints / e_swing;
  EXPECT_LT(bound, 0.1 * ds(0));  // the joints' start-up is small against the swing
  EXPECT_LT((a.r - b.r).head<2>().norm(), bound) << "energy ratio " << e_joints / e_swing;
  ::testing::Test::RecordProperty("difference_m", std::to_string((a.r - b.r).head<2>().norm()));
  ::testing::Test::RecordProperty("bound_m", std::to_string(bound));
}
