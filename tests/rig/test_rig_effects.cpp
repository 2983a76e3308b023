// The physical signature of every effect of the catalogue, each against the
// effect-free rig and a closed form: friction and drag by how a released swing
// decays, stiffness and mass by the linear modes, geometry errors by where
// the body hangs, the measurement chain by the recorded signals.
//
// Most cases use the trifilar of pendulum_closed_form.yaml (3 vertical rods
// of L = 1 m at R = 0.4 m, a 100 kg disk with its CoG in the joint plane): a
// sideways displacement makes the body translate on a parallelogram, a plane
// pendulum of length l = L + g / (2 pi kRigidRodHz)^2 (the rigid rods'
// static stretch) and weight W = m g.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "rig/effects.hpp"
#include "rig/encoder.hpp"
#include "rig/linearization.hpp"
#include "support/rig_cases.hpp"
#include "rig/simulation.hpp"

using namespace rigflex;
using rig::Vec3;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;  // multifilar_rig's gravity

// Pendulum length of a rig with rigid rods: L plus the stretch g / w^2 of the 300 Hz rod springs.
double rigid_pendulum_length(double L) { return L + kG / std::pow(2 * kPi * rig::kRigidRodHz, 2); }

struct Peak {
  double t = 0, amplitude = 0;  // |extremum| of the signal
};

// Interior extrema of x (maxima and minima, i.e. one per half cycle), refined by
// a parabola through the three samples around each. With >= 100 samples per
// 2 s period the parabola's error is ~ (omega dt)^4 ~ 1e-7 of the amplitude.
std::vector<Peak> half_cycle_peaks(const Eigen::VectorXd& t, const Eigen::VectorXd& x) {
  std::vector<Peak> out;
  for (Eigen::Index k = 1; k + 1 < x.size(); ++k) {
    const bool max = x(k) > x(k - 1) && x(k) >= x(k + 1);
    const bool min = x(k) < x(k - 1) && x(k) <= x(k + 1);
    if (!max && !min) continue;
    const double a = x(k - 1), b = x(k), c = x(k + 1);
    const double den = a - 2 * b + c;
    const double p = den != 0 ? 0.5 * (a - c) / den : 0.0;
    out.push_back({t(k) + p * (t(k) - t(k - 1)), std::abs(b - 0.25 * (a - c) * p)});
  }
  return out;
}

// The sideways lean u_x of rod `rod`, rebuilt from its encoders (as a user of
// the measurement files would): sin of the swing angle for a sway along x.
Eigen::VectorXd lean_x(const rig::RigModel& model, const rig::Record& h, int rod = 0) {
  Eigen::VectorXd ux(h.t.size());
  for (Eigen::Index k = 0; k < h.t.size(); ++k) {
    ux(k) = rig::rod_direction(model.geometry.rods[rod].encoder_axis, {h.alpha(k, rod), h.beta(k, rod)}).x();
  }
  return ux;
}

// A sway along x released from x0 (m), recorded for `duration` s: the peaks of the rod lean.
std::vector<Peak> sway_peaks(const rig::RigModel& model, double x0, double duration) {
  const rig::RigSystem rig(model);
  const rig::Equilibrium eq = rig::static_equilibrium(rig);
  EXPECT_TRUE(eq.converged) << eq.message;
  rig::HistoryRequest req;
  req.initial = rig::InitialCondition{x0, 0.0, 0.0, Vec3::Zero(), Vec3::Zero()};
  req.duration_s = duration;
  const rig::Record h = rig::simulate_history(rig, eq.configuration, req);
  return half_cycle_peaks(h.t, lean_x(model, h));
}

// Root-mean-square misfit of the peak amplitudes by a straight line and by an
// exponential (a line through the logarithms), both in amplitude units.
struct DecayFits {
  double linear_rms = 0, exponential_rms = 0;
};
DecayFits fit_decay(const std::vector<Peak>& p) {
  const int n = static_cast<int>(p.size());
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd y(n), ly(n);
  for (int k = 0; k < n; ++k) {
    A(k, 0) = 1.0;
    A(k, 1) = p[k].t;
    y(k) = p[k].amplitude;
    ly(k) = std::log(p[k].amplitude);
  }
  const Eigen::Vector2d lin = A.colPivHouseholderQr().solve(y);
  const Eigen::Vector2d ex = A.colPivHouseholderQr().solve(ly);
  DecayFits f;
  f.linear_rms = std::sqrt((A * lin - y).squaredNorm() / n);
  f.exponential_rms = std::sqrt(((A * ex).array().exp().matrix() - y).squaredNorm() / n);
  return f;
}

double max_relative_spread(const std::vector<double>& v) {
  double mean = 0;
  for (double x : v) mean += x / v.size();
  double worst = 0;
  for (double x : v) worst = std::max(worst, std::abs(x - mean) / std::abs(mean));
  return worst;
}

double mean_of(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m += x / v.size();
  return m;
}

// The mode (any kind) in which coordinate j has the largest kinetic energy share.
const rig::RigMode& mode_along(const rig::Linearization& lin, int j) {
  const rig::RigMode* best = &lin.modes.front();
  double best_share = -1;
  for (const auto& m : lin.modes) {
    const double share = m.shape(j) * (lin.M * m.shape)(j);
    if (share > best_share) best_share = share, best = &m;
  }
  return *best;
}

rig::Configuration equilibrium_of(const rig::RigModel& model) {
  const rig::RigSystem rig(model);
  const rig::Equilibrium eq = rig::static_equilibrium(rig);
  EXPECT_TRUE(eq.converged) << eq.message;
  return eq.configuration;
}

// Lower joint centres in G at a configuration.
std::vector<Vec3> lower_joints(const rig::RigModel& model, const rig::Configuration& c) {
  const rig::RigSystem rig(model);
  std::vector<Vec3> B;
  for (const auto& r : rig.kinematics(c, rig.at_rest(), 0.0).rods) B.push_back(r.B);
  return B;
}

// Measured values, for the test report (--gtest_output=xml).
void record(const std::string& key, const std::vector<double>& values) {
  std::ostringstream os;
  os.precision(7);
  for (double v : values) os << v << ' ';
  ::testing::Test::RecordProperty(key, os.str());
}

}  // namespace

// ---------------------------------------------------------------------------
// joint_friction
// ---------------------------------------------------------------------------

TEST(RigEffects, JointFrictionCoulombDecaysLinearlyViscousExponentially) {
  // Sway of the trifilar from x0 = 0.05 m (lean 0.05 rad). Each rod has two
  // joints turning at the swing rate theta'.
  //  * Coulomb mu: 2 n joints each dissipate mu |theta'|: per half cycle the
  //    amplitude drops by the constant 4 n mu / (W l) (the friction moves the
  //    centre of oscillation by half of that to either side): a linear decay.
  //  * viscous c: m l^2 theta'' + 2 n c theta' + W l theta = 0, decay rate
  //    sigma = n c / (m l^2): successive half-cycle peaks in the constant ratio
  //    exp(-sigma pi / omega_d): an exponential decay.
  const int n = 3;
  const double m = 100.0, L = 1.0, x0 = 0.05, duration = 6.5;
  const double l = rigid_pendulum_length(L), W = m * kG;
  rig::RigModel base = test::multifilar_rig(n, 0.4, L, m, 0.5, 0.0);
  base.sensors.sample_rate_hz = 100;

  // Frictionless: the peaks are constant. The integrator's relative
  // tolerance (1e-8) and the parabolic peak fit (1e-7) bound the scatter.
  const std::vector<Peak> undamped = sway_peaks(base, x0, duration);
  ASSERT_GE(undamped.size(), 6u);
  double spread_undamped = 0;
  for (const Peak& p : undamped) {
    spread_undamped = std::max(spread_undamped, std::abs(p.amplitude / undamped[0].amplitude - 1));
  }
  EXPECT_LT(spread_undamped, 1e-5);
  record("undamped_peak_spread", {spread_undamped});

  // Coulomb only.
  rig::JointFrictionParameters coulomb;
  coulomb.coulomb = 0.5;  // N m: 4 n mu / (W l) = 6.1e-3 per half cycle, the lean falls from 0.05 to ~0.013
  rig::RigModel mc = base;
  mc.effects.push_back(std::make_shared<rig::JointFriction>(coulomb));
  const std::vector<Peak> pc = sway_peaks(mc, x0, duration);
  ASSERT_GE(pc.size(), 6u);
  std::vector<double> drop, ratio;
  for (size_t k = 1; k < pc.size(); ++k) {
    drop.push_back(pc[k - 1].amplitude - pc[k].amplitude);
    ratio.push_back(pc[k].amplitude / pc[k - 1].amplitude);
  }
  const double drop_expected = 4.0 * n * coulomb.coulomb / (W * l);
  // Constant decrement; the regularization (eps = 1e-3 rad/s against peak
  // rates of 0.04-0.15 rad/s: ~ (eps / rate)^2 < 1e-3) and sin(theta) ~
  // theta (theta^2 / 6 < 5e-4) perturb it by well below 0.5 %. The ratio of
  // successive peaks falls steadily instead (0.88 to 0.69).
  EXPECT_LT(max_relative_spread(drop), 0.005);
  EXPECT_NEAR(mean_of(drop), drop_expected, 0.005 * drop_expected);
  EXPECT_GT(max_relative_spread(ratio), 0.05);
  const DecayFits fc = fit_decay(pc);
  EXPECT_LT(fc.linear_rms, 0.1 * fc.exponential_rms) << "linear " << fc.linear_rms << ", exponential "
                                                    << fc.exponential_rms;
  record("coulomb_first_last_peak", {pc.front().amplitude, pc.back().amplitude});
  record("coulomb_drop_mean_expected_spread", {mean_of(drop), drop_expected, max_relative_spread(drop)});
  record("coulomb_ratio_spread", {max_relative_spread(ratio)});
  record("coulomb_rms_linear_exponential", {fc.linear_rms, fc.exponential_rms});

  // Viscous only.
  rig::JointFrictionParameters viscous;
  viscous.viscous = 20.0 / 3.0;  // N m s/rad: sigma = n c / (m l^2) = 0.2 /s, ratio 0.818 per half cycle
  rig::RigModel mv = base;
  mv.effects.push_back(std::make_shared<rig::JointFriction>(viscous));
  const std::vector<Peak> pv = sway_peaks(mv, x0, duration);
  ASSERT_GE(pv.size(), 6u);
  std::vector<double> drop_v, ratio_v;
  for (size_t k = 1; k < pv.size(); ++k) {
    drop_v.push_back(pv[k - 1].amplitude - pv[k].amplitude);
    ratio_v.push_back(pv[k].amplitude / pv[k - 1].amplitude);
  }
  const double sigma = n * viscous.viscous / (m * l * l);
  const double omega_d = std::sqrt(kG / l - sigma * sigma);
  const double ratio_expected = std::exp(-sigma * kPi / omega_d);
  // A linear oscillator: constant ratio to the peak-fit precision; the
  // pendulum's sin nonlinearity at 0.05 rad moves omega by theta^2 / 16 =
  // 1.6e-4 and the ratio by ~3e-5: 5e-4 allowed.
  EXPECT_LT(max_relative_spread(ratio_v), 5e-4);
  EXPECT_NEAR(mean_of(ratio_v), ratio_expected, 5e-4);
  EXPECT_GT(max_relative_spread(drop_v), 0.2);  // the decrement shrinks with the amplitude
  const DecayFits fv = fit_decay(pv);
  EXPECT_LT(fv.exponential_rms, 0.1 * fv.linear_rms) << "linear " << fv.linear_rms << ", exponential "
                                                     << fv.exponential_rms;
  record("viscous_ratio_mean_expected_spread", {mean_of(ratio_v), ratio_expected, max_relative_spread(ratio_v)});
  record("viscous_drop_spread", {max_relative_spread(drop_v)});
  record("viscous_rms_linear_exponential", {fv.linear_rms, fv.exponential_rms});
}

// ---------------------------------------------------------------------------
// air_drag
// ---------------------------------------------------------------------------

TEST(RigEffects, AirDragDecaysLargeSwingsFasterThanSmallOnes) {
  // Quadratic drag F = -k |v| v, k = rho CdA / 2, on a pendulum swinging
  // x = A cos(omega t) takes (4/3) k omega^2 A^3 per half cycle out of the
  // energy m omega^2 A^2 / 2: A drops by (4/3) (k / m) A^2. In lean angles,
  // 1 / theta grows by c = (4/3) k l / m each half cycle, whatever the
  // amplitude, and the relative decay per half cycle, c theta, is
  // proportional to the amplitude: 5 times larger at 0.1 m than at 0.02 m.
  const double m = 100.0, L = 1.0, duration = 4.5;
  const double l = rigid_pendulum_length(L);
  rig::RigModel base = test::multifilar_rig(3, 0.4, L, m, 0.5, 0.0);
  base.sensors.sample_rate_hz = 100;
  rig::AirDragParameters drag;
  drag.cd_area = 50.0;  // m^2 (a big sail on a light body, to see it in 2 cycles): c = 0.4
  rig::RigModel md = base;
  md.effects.push_back(std::make_shared<rig::AirDrag>(drag));
  const double k = 0.5 * drag.density * drag.cd_area;
  const double c_expected = 4.0 / 3.0 * k * l / m;

  auto relative_decay_and_c = [](const std::vector<Peak>& p) {
    std::vector<double> rel, c;
    for (size_t i = 1; i < p.size(); ++i) {
      rel.push_back(1 - p[i].amplitude / p[i - 1].amplitude);
      c.push_back(1 / p[i].amplitude - 1 / p[i - 1].amplitude);
    }
    return std::pair{rel, c};
  };
  const std::vector<Peak> big = sway_peaks(md, 0.10, duration);
  const std::vector<Peak> small = sway_peaks(md, 0.02, duration);
  ASSERT_GE(big.size(), 4u);
  ASSERT_GE(small.size(), 4u);
  const auto [rel_big, c_big] = relative_decay_and_c(big);
  const auto [rel_small, c_small] = relative_decay_and_c(small);
  // The first half cycle: 0.1 m loses ~4 %, 0.02 m ~0.8 %. The ratio is below
  // 5 because the large swing has already decayed more by its first peak.
  const double ratio = rel_big[0] / rel_small[0];
  EXPECT_GT(ratio, 4.0) << "relative decay " << rel_big[0] << " at 0.1 m, " << rel_small[0] << " at 0.02 m";
  EXPECT_LT(ratio, 5.5);
  // 1 / theta grows by the same c at both amplitudes; the energy argument
  // holds to first order in the decay per half cycle (<= 4 %, its second
  // order ~ 0.1 %) and in theta^2 (theta^2 / 8 ~ 0.1 %): 1 % allowed.
  for (double c : c_big) EXPECT_NEAR(c, c_expected, 0.01 * c_expected);
  for (double c : c_small) EXPECT_NEAR(c, c_expected, 0.01 * c_expected);
  record("drag_c_big", c_big);
  record("drag_c_small", c_small);
  record("drag_c_expected", {c_expected});
  record("drag_relative_decay_big_small_ratio", {rel_big[0], rel_small[0], ratio});

  // Zero translational drag (only a rotational coefficient, which a pure
  // sway does not excite): no decay, as without the effect.
  rig::AirDragParameters rotational_only;
  rotational_only.rotational = 5.0;
  rig::RigModel m0 = base;
  m0.effects.push_back(std::make_shared<rig::AirDrag>(rotational_only));
  const std::vector<Peak> none = sway_peaks(m0, 0.10, duration);
  ASSERT_GE(none.size(), 4u);
  for (const Peak& p : none) EXPECT_NEAR(p.amplitude / none[0].amplitude, 1.0, 1e-5);
  {
    double worst = 0;
    for (const Peak& p : none) worst = std::max(worst, std::abs(p.amplitude / none[0].amplitude - 1));
    record("drag_none_spread", {worst});
  }
}

// ---------------------------------------------------------------------------
// rod_compliance
// ---------------------------------------------------------------------------

TEST(RigEffects, RodComplianceAddsTheBounceModeOfTheRodStiffness) {
  // Three vertical rods of unequal stiffness k = (1, 2, 4) MN/m at radii
  // r_i = 0.8 m / (k_i / 1 MN/m) (0.8, 0.4, 0.2 m), 120 degrees apart, so that
  // sum k_i b_i = 0: the stiffness centre lies under the CoG (in the joint
  // plane, at P), vertical translation is uncoupled from tilt in K and M, and
  // the body sinks and bounces as one mass on the three parallel springs:
  // static sink W / sum k, bounce sqrt(sum k / m) / 2 pi = 42.11 Hz.
  const double m = 100.0, L = 1.0;
  const std::vector<double> k = {1.0e6, 2.0e6, 4.0e6};
  rig::RigModel model = test::multifilar_rig(3, 0.4, L, m, 0.5, 0.0);
  for (int i = 0; i < 3; ++i) {
    auto& rod = model.geometry.rods[i];
    rod.lower = rod.lower.normalized() * (0.8e6 / k[i]);
    rod.upper = rod.lower + Vec3(0, 0, L);
  }
  // Without the effect the rods are rigid: their 300 Hz modes are constraints, no deformation mode.
  {
    const rig::Linearization lin = rig::linearize(rig::RigSystem(model));
    int deformation = 0, constraint = 0;
    for (const auto& md : lin.modes) {
      deformation += md.kind == rig::RigModeKind::deformation;
      constraint += md.kind == rig::RigModeKind::rod_constraint;
    }
    EXPECT_EQ(deformation, 0);
    EXPECT_EQ(constraint, 3);
  }
  model.effects.push_back(std::make_shared<rig::RodCompliance>(k));
  const rig::RigSystem rig(model);
  const rig::Linearization lin = rig::linearize(rig);
  const double ksum = k[0] + k[1] + k[2];
  // Static sink: exact for linear springs, up to the equilibrium tolerance (1e-10 of W over sum k).
  const rig::Configuration& c = lin.equilibrium.configuration;
  EXPECT_NEAR(c.r.z(), -m * kG / ksum, 1e-9 * m * kG / ksum);
  EXPECT_LT(c.q.vec().norm(), 1e-9);  // no tilt
  const rig::RigMode& bounce = mode_along(lin, 2);
  EXPECT_EQ(bounce.kind, rig::RigModeKind::deformation);
  const double f_expected = std::sqrt(ksum / m) / (2 * kPi);
  // Central differences with steps of 1e-6 L: ~1e-6 truncation (see linearization.cpp).
  EXPECT_NEAR(bounce.frequency_hz, f_expected, 1e-5 * f_expected);
  // The mode is a pure vertical translation: the other coordinates carry < 1e-6 of its kinetic energy.
  const Eigen::VectorXd Ms = lin.M * bounce.shape;
  EXPECT_GT(bounce.shape(2) * Ms(2), 1 - 1e-6);
  int deformation = 0;
  for (const auto& md : lin.modes) deformation += md.kind == rig::RigModeKind::deformation;
  EXPECT_EQ(deformation, 3);  // bounce and the two tilts
  record("sink_measured_expected", {c.r.z(), -m * kG / ksum});
  record("bounce_hz_measured_expected_share", {bounce.frequency_hz, f_expected, bounce.shape(2) * Ms(2)});
}

// ---------------------------------------------------------------------------
// rod_mass
// ---------------------------------------------------------------------------

TEST(RigEffects, RodMassActsAsAThirdAtTheLowerJointAndHalfItsWeight) {
  // Uniform rods of mass mr swinging about their upper joints: kinetic energy
  // of mr/3 at the lower joint, potential energy of mr/2 there. Sway (the body
  // translates, every rod swings by theta):
  //   omega^2 = g (m + n mr / 2) / (l (m + n mr / 3))     -> up 1.18 % here
  // (the rod alone is a compound pendulum of length 2L/3, faster than the
  // body's). Yaw psi (rods lean by R psi / l):
  //   omega^2 = g R^2 (m + n mr / 2) / (l (J + n mr R^2 / 3))  -> down 3.06 %
  // here, because the disk's J = m Rd^2 / 2 is small against m R^2 at R = 0.6 m.
  const int n = 3;
  const double m = 100.0, L = 1.0, R = 0.6, Rd = 0.5, mr = 5.0;
  const double J = m * Rd * Rd / 2;
  rig::RigModel base = test::multifilar_rig(n, R, L, m, Rd, 0.0);
  rig::RigModel heavy = base;
  heavy.effects.push_back(std::make_shared<rig::RodMass>(std::vector<double>(n, mr)));
  const rig::RigSystem rig0(base), rig1(heavy);
  const rig::Linearization lin0 = rig::linearize(rig0);
  const rig::Linearization lin1 = rig::linearize(rig1);
  const double sway_ratio = std::sqrt((m + n * mr / 2) / (m + n * mr / 3));
  const double yaw_ratio = std::sqrt((m + n * mr / 2) / m * J / (J + n * mr * R * R / 3));
  // The rigid rods' static stretch differs between the two rigs by 2 % of
  // 2.8e-6 m (the 300 Hz springs scale with the moving mass, the load with
  // the weight): 6e-8 of l. The ratios are exact up to that and the
  // linearization's ~1e-6.
  EXPECT_NEAR(test::swing_frequency_along(lin1, 0) / test::swing_frequency_along(lin0, 0), sway_ratio, 1e-5);
  EXPECT_NEAR(test::swing_frequency_along(lin1, 5) / test::swing_frequency_along(lin0, 5), yaw_ratio, 1e-5);
  EXPECT_GT(test::swing_frequency_along(lin1, 0), test::swing_frequency_along(lin0, 0));
  EXPECT_LT(test::swing_frequency_along(lin1, 5), test::swing_frequency_along(lin0, 5));

  // Statics: the lower end of each rod (the spring) carries its share of the
  // body plus half the rod's weight; the load cell at the upper end
  // (simulation.hpp: spring force + half the rod's weight along it) carries
  // the whole rod in addition.
  const rig::SensorSample s0 = rig::read_sensors(rig0, lin0.equilibrium.configuration, rig0.at_rest(), 0.0);
  const rig::SensorSample s1 = rig::read_sensors(rig1, lin1.equilibrium.configuration, rig1.at_rest(), 0.0);
  const rig::Kinematics k0 = rig0.kinematics(lin0.equilibrium.configuration, rig0.at_rest(), 0.0);
  const rig::Kinematics k1 = rig1.kinematics(lin1.equilibrium.configuration, rig1.at_rest(), 0.0);
  const double rod_weight = mr * kG;
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(s0.force(i), m * kG / n, 1e-9 * m * kG);
    EXPECT_NEAR(k1.rods[i].force - k0.rods[i].force, 0.5 * rod_weight, 1e-9 * m * kG);
    EXPECT_NEAR(s1.force(i) - s0.force(i), rod_weight, 1e-9 * m * kG);
  }
  EXPECT_NEAR(rig1.suspended_weight() - rig0.suspended_weight(), n * 0.5 * rod_weight, 1e-9 * m * kG);
  record("sway_ratio_measured_expected",
         {test::swing_frequency_along(lin1, 0) / test::swing_frequency_along(lin0, 0), sway_ratio});
  record("yaw_ratio_measured_expected", {test::swing_frequency_along(lin1, 5) / test::swing_frequency_along(lin0, 5), yaw_ratio});
  record("rod1_spring_and_cell_increase_N", {k1.rods[0].force - k0.rods[0].force, s1.force(0) - s0.force(0)});
}

// ---------------------------------------------------------------------------
// encoder_offset, load_cell_gain
// ---------------------------------------------------------------------------

namespace {

// A swing with sway and yaw (every encoder and load cell moves), noise off.
rig::Record measured_swing(const rig::RigModel& model) {
  const rig::RigSystem rig(model);
  const rig::Equilibrium eq = rig::static_equilibrium(rig);
  EXPECT_TRUE(eq.converged) << eq.message;
  rig::HistoryRequest req;
  req.initial = rig::InitialCondition{0.03, -0.02, 0.02, Vec3::Zero(), Vec3::Zero()};
  req.duration_s = 2.0;
  req.noise_seed = 7;
  return rig::simulate_history(rig, eq.configuration, req);
}

rig::RigModel measured_rig() {
  rig::RigModel model = test::multifilar_rig(3, 0.5, 1.2, 300.0, 0.7, 0.2);
  model.sensors.sample_rate_hz = 100;
  return model;
}

}  // namespace

TEST(RigEffects, EncoderOffsetShiftsTheAnglesByExactlyTheOffset) {
  // The offset sits in the measurement chain only: the motion is the same
  // computation bit for bit, so alpha and beta differ by the offset up to
  // the rounding of one addition (1e-16 of the angle; 1e-12 allowed).
  const rig::RigModel base = measured_rig();
  rig::RigModel off = base;
  const std::vector<double> da = {0.01, -0.02, 0.005}, db = {-0.003, 0.0, 0.015};
  off.effects.push_back(std::make_shared<rig::EncoderOffset>(da, db));
  const rig::Record h0 = measured_swing(base);
  const rig::Record h1 = measured_swing(off);
  ASSERT_EQ(h0.t.size(), h1.t.size());
  EXPECT_GT(h0.alpha.col(0).maxCoeff() - h0.alpha.col(0).minCoeff(), 1e-3);  // it moves
  EXPECT_GT(h0.beta.col(0).maxCoeff() - h0.beta.col(0).minCoeff(), 1e-3);
  double worst = 0;
  for (int i = 0; i < 3; ++i) {
    const double scale = 1e-12 * std::max({h1.alpha.col(i).cwiseAbs().maxCoeff(), h1.beta.col(i).cwiseAbs().maxCoeff()});
    const double ea = (h1.alpha.col(i).array() - h0.alpha.col(i).array() - da[i]).abs().maxCoeff();
    const double eb = (h1.beta.col(i).array() - h0.beta.col(i).array() - db[i]).abs().maxCoeff();
    EXPECT_LE(ea, scale);
    EXPECT_LE(eb, scale);
    worst = std::max({worst, ea, eb});
  }
  record("max_angle_error_rad", {worst});
  EXPECT_EQ(h1.force, h0.force);  // the load cells do not see it
}

TEST(RigEffects, LoadCellGainScalesAndOffsetsTheForcesExactly) {
  // Load cell i reads gain_i F_i + offset_i, the motion untouched: to the
  // rounding of one multiply-add (1e-16; 1e-12 of the reading allowed).
  const rig::RigModel base = measured_rig();
  rig::RigModel cal = base;
  const std::vector<double> gain = {1.02, 0.97, 1.0}, offset = {15.0, -8.0, 0.0};
  cal.effects.push_back(std::make_shared<rig::LoadCellGain>(gain, offset));
  const rig::Record h0 = measured_swing(base);
  const rig::Record h1 = measured_swing(cal);
  ASSERT_EQ(h0.t.size(), h1.t.size());
  EXPECT_GT(h0.force.col(0).maxCoeff() - h0.force.col(0).minCoeff(), 1.0);  // the forces swing (N)
  double worst = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::ArrayXd expected = gain[i] * h0.force.col(i).array() + offset[i];
    const double err = (h1.force.col(i).array() - expected).abs().maxCoeff() / expected.abs().maxCoeff();
    EXPECT_LE(err, 1e-12);
    worst = std::max(worst, err);
  }
  record("max_relative_force_error", {worst});
  EXPECT_EQ(h1.alpha, h0.alpha);  // the encoders do not see it
  EXPECT_EQ(h1.beta, h0.beta);
}

// ---------------------------------------------------------------------------
// rod_length_error, joint_position_error
// ---------------------------------------------------------------------------

TEST(RigEffects, RodLengthErrorLowersTheBodyByTheExtraLength) {
  // Vertical rods. All rods longer by d: the body hangs d lower, nothing else
  // changes (the rigid rods' stretch is the same); exact up to the
  // equilibrium tolerance (1e-10 W over the rod stiffness ~ 1e-15 m), so
  // 1e-6 of d is a wide bound.
  const double d = 4e-3;
  const rig::RigModel base = test::multifilar_rig(3, 0.4, 1.0, 100.0, 0.5, 0.0);
  const rig::Configuration c0 = equilibrium_of(base);
  rig::RigModel longer = base;
  longer.effects.push_back(std::make_shared<rig::RodLengthError>(std::vector<double>(3, d)));
  const rig::Configuration c1 = equilibrium_of(longer);
  EXPECT_NEAR(c1.r.z() - c0.r.z(), -d, 1e-6 * d);
  EXPECT_LT((c1.r - c0.r).head<2>().norm(), 1e-6 * d);
  EXPECT_LT(c1.q.angularDistance(c0.q), 1e-6 * d);

  // Rod 1 alone longer by d: its lower joint drops by d, the other two stay,
  // so the body tilts about the line B2 B3 by theta = d / (1.5 R) (the
  // distance of B1 from that line) and P (the joints' centroid) drops d / 3.
  // The tilt moves the joints sideways by ~ theta^2 R = 2e-5 m, which changes
  // a rod's vertical reach by (2e-5)^2 / 2L = 2e-10 m: the heights hold to
  // 1e-6 d; the angle to sin(theta) ~ theta, theta^2 / 6 = 7e-6 (1e-4 allowed).
  rig::RigModel one = base;
  one.effects.push_back(std::make_shared<rig::RodLengthError>(std::vector<double>{d, 0.0, 0.0}));
  const rig::Configuration c2 = equilibrium_of(one);
  const std::vector<Vec3> B0 = lower_joints(base, c0), B2 = lower_joints(one, c2);
  EXPECT_NEAR(B2[0].z() - B0[0].z(), -d, 1e-6 * d);
  EXPECT_NEAR(B2[1].z() - B0[1].z(), 0.0, 1e-6 * d);
  EXPECT_NEAR(B2[2].z() - B0[2].z(), 0.0, 1e-6 * d);
  EXPECT_NEAR(c2.r.z() - c0.r.z(), -d / 3, 1e-6 * d);
  // The tilt: a rotation by +theta about e = b1_hat x z raises b1
  // ((b1_hat x z) x b1 = |b1| z), so lowering B1 is -d / (1.5 R) about e.
  const Eigen::AngleAxisd tilt(c2.q * c0.q.conjugate());
  const Vec3 e = base.geometry.rods[0].lower.normalized().cross(Vec3::UnitZ());
  EXPECT_NEAR(tilt.angle() * tilt.axis().dot(e), -d / (1.5 * 0.4), 1e-4 * d / (1.5 * 0.4));
  record("all_longer_dz_error_m", {c1.r.z() - c0.r.z() + d});
  record("one_longer_dB1_dB2_dB3_dP_m", {B2[0].z() - B0[0].z(), B2[1].z() - B0[1].z(), B2[2].z() - B0[2].z(),
                                         c2.r.z() - c0.r.z()});
  record("one_longer_tilt_measured_expected", {tilt.angle() * tilt.axis().dot(e), -d / (1.5 * 0.4)});
}

namespace {

// Rigid vertical rods of unchanged length hang straight below their upper
// joints: moving every upper joint by e (G) moves the body by e; moving every
// lower joint by e (frame c) moves the body by -e (the joints must stay
// under the same upper joints). The upper case is exact; in the lower case
// the CoG is no longer under the joints' centroid, the rods share the load
// unequally (by 2 |e_h| / R) and their 2.8e-6 m static stretch differs
// accordingly: a tilt of ~ 2.8e-6 (2 |e_h| / R) / R, 4e-7 rad for
// |e_h| = 1.2 cm, 1e-8 rad for 0.25 mm; 1e-6 rad allowed.
void expect_body_follows_the_joints(const Vec3& e) {
  const rig::RigModel base = test::multifilar_rig(3, 0.4, 1.0, 100.0, 0.5, 0.0);
  const rig::Configuration c0 = equilibrium_of(base);
  rig::RigModel up = base;
  up.effects.push_back(
      std::make_shared<rig::JointPositionError>(std::vector<Vec3>(3, e), std::vector<Vec3>(3, Vec3::Zero())));
  const rig::Configuration cu = equilibrium_of(up);
  EXPECT_LT((cu.r - c0.r - e).norm(), 1e-6 * e.norm()) << "body moved by " << (cu.r - c0.r).transpose();
  EXPECT_LT(cu.q.angularDistance(c0.q), 1e-9);
  rig::RigModel low = base;
  low.effects.push_back(
      std::make_shared<rig::JointPositionError>(std::vector<Vec3>(3, Vec3::Zero()), std::vector<Vec3>(3, e)));
  const rig::Configuration cl = equilibrium_of(low);
  EXPECT_LT((cl.r - c0.r + e).norm(), 1e-6 * e.norm()) << "body moved by " << (cl.r - c0.r).transpose();
  EXPECT_LT(cl.q.angularDistance(c0.q), 1e-6);
  record("upper_position_error_tilt", {(cu.r - c0.r - e).norm(), cu.q.angularDistance(c0.q)});
  record("lower_position_error_tilt", {(cl.r - c0.r + e).norm(), cl.q.angularDistance(c0.q)});
}

}  // namespace

TEST(RigEffects, JointPositionErrorMovesAndTiltsTheBodyWithTheJoints) {
  // Sub-millimetre horizontal errors (with a 3 mm vertical one): see above.
  expect_body_follows_the_joints(Vec3(2.0e-4, -1.5e-4, 3.0e-3));

  // Upper joint of rod 1 raised by h: B1 rises h (B2, B3 stay), the body
  // tilts the other way from a longer rod: +h / (1.5 R) about b1_hat x z.
  // Tolerances as for the rod length error of the same size.
  const double h = 4e-3;
  const rig::RigModel base = test::multifilar_rig(3, 0.4, 1.0, 100.0, 0.5, 0.0);
  const rig::Configuration c0 = equilibrium_of(base);
  rig::RigModel raised = base;
  std::vector<Vec3> upper(3, Vec3::Zero());
  upper[0] = Vec3(0, 0, h);
  raised.effects.push_back(std::make_shared<rig::JointPositionError>(upper, std::vector<Vec3>(3, Vec3::Zero())));
  const rig::Configuration c3 = equilibrium_of(raised);
  const std::vector<Vec3> B0 = lower_joints(base, c0), B3 = lower_joints(raised, c3);
  EXPECT_NEAR(B3[0].z() - B0[0].z(), h, 1e-6 * h);
  EXPECT_NEAR(B3[1].z() - B0[1].z(), 0.0, 1e-6 * h);
  EXPECT_NEAR(B3[2].z() - B0[2].z(), 0.0, 1e-6 * h);
  EXPECT_NEAR(c3.r.z() - c0.r.z(), h / 3, 1e-6 * h);
  const Eigen::AngleAxisd tilt(c3.q * c0.q.conjugate());
  const Vec3 axis = base.geometry.rods[0].lower.normalized().cross(Vec3::UnitZ());
  EXPECT_NEAR(tilt.angle() * tilt.axis().dot(axis), h / (1.5 * 0.4), 1e-4 * h / (1.5 * 0.4));
  record("raised_dB1_dB2_dB3_dP_m", {B3[0].z() - B0[0].z(), B3[1].z() - B0[1].z(), B3[2].z() - B0[2].z(),
                                     c3.r.z() - c0.r.z()});
  record("raised_tilt_measured_expected", {tilt.angle() * tilt.axis().dot(axis), h / (1.5 * 0.4)});
}

TEST(RigEffects, JointPositionErrorOfACentimetreMovesTheBodyWithTheJoints) {
  // The equilibrium lies a centimetre from the nominal pose: the trust
  // region walks the valley of constant rod lengths to it.
  expect_body_follows_the_joints(Vec3(0.01, -0.006, 0.003));
}

// ---------------------------------------------------------------------------
// fixed_frame_flexibility, carrying_frame_flexibility
// ---------------------------------------------------------------------------

TEST(RigEffects, FixedFrameFlexibilitySagsAndSlowsTheSway) {
  // Each upper joint on its own isotropic spring kf to ground with mass mf.
  // Statics: each spring carries W / n: the body hangs W / (n kf) lower.
  // Sway along x (rods vertical, forces in the joint plane through P: no
  // tilt): body x_b and the three joints x_j together,
  //   m x_b'' = -(W / l)(x_b - x_j),  n mf x_j'' = (W / l)(x_b - x_j) - n kf x_j,
  // a 2-DOF system whose lower frequency is the sway.
  const int n = 3;
  const double m = 100.0, L = 1.0, kf = 2.0e4, mf = 10.0;
  const double W = m * kG, l = rigid_pendulum_length(L);
  const rig::RigModel base = test::multifilar_rig(n, 0.4, L, m, 0.5, 0.0);
  rig::FixedFrameModel ff;
  ff.K = kf * Eigen::MatrixXd::Identity(3 * n, 3 * n);
  ff.M = mf * Eigen::MatrixXd::Identity(3 * n, 3 * n);
  ff.C = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  ff.joint_row = {0, 3, 6};
  ff.source = "test springs";
  rig::RigModel flex = base;
  flex.effects.push_back(std::make_shared<rig::FixedFrameFlexibility>(ff));
  const rig::Linearization lin0 = rig::linearize(rig::RigSystem(base));
  const rig::Linearization lin1 = rig::linearize(rig::RigSystem(flex));
  const rig::Configuration& c0 = lin0.equilibrium.configuration;
  const rig::Configuration& c1 = lin1.equilibrium.configuration;
  EXPECT_NEAR(c1.r.z() - c0.r.z(), -W / (n * kf), 1e-8 * W / (n * kf));
  for (int i = 0; i < n; ++i) EXPECT_NEAR(c1.xf(3 * i + 2), -W / (n * kf), 1e-8 * W / (n * kf));

  const double a = W / l, b = n * kf, M1 = m, M2 = n * mf;
  // det([[a - lam M1, -a], [-a, a + b - lam M2]]) = 0
  const double A2 = M1 * M2, A1 = -(a * M2 + (a + b) * M1), A0 = a * b;
  const double lam = (-A1 - std::sqrt(A1 * A1 - 4 * A2 * A0)) / (2 * A2);
  const double f_expected = std::sqrt(lam) / (2 * kPi);
  const double f_rigid = test::swing_frequency_along(lin0, 0), f_flex = test::swing_frequency_along(lin1, 0);
  EXPECT_NEAR(f_flex, f_expected, 1e-5 * f_expected);
  // 0.81 % slower: the frame's n kf = 6e4 N/m in series with the pendulum's W / l = 981 N/m.
  EXPECT_LT(f_flex, f_rigid * (1 - 0.005));
  record("sag_measured_expected", {c1.r.z() - c0.r.z(), -W / (n * kf)});
  record("sway_hz_rigid_flexible_expected", {f_rigid, f_flex, f_expected});
}

TEST(RigEffects, CarryingFrameModeIsStiffenedByThePendulum) {
  // One elastic mode of the carrying frame: every lower joint moves radially
  // by s per unit modal coordinate (zero net force and moment on the body at
  // P, so the mode is uncoupled from the rigid motions). The rods stay
  // vertical: each rod's pendulum stiffness (W / n) / l resists the joint's
  // sideways motion, so eta'' + (omega2 + W s^2 / l) eta = 0.
  const int n = 3;
  const double m = 100.0, L = 1.0, s = 0.1, f_frame = 5.0;
  const double W = m * kG, l = rigid_pendulum_length(L);
  rig::RigModel model = test::multifilar_rig(n, 0.4, L, m, 0.5, 0.0);
  rig::CarryingFrameModel cf;
  cf.psi = Eigen::MatrixXd::Zero(3 * n, 1);
  for (int i = 0; i < n; ++i) cf.psi.block<3, 1>(3 * i, 0) = s * model.geometry.rods[i].lower.normalized();
  cf.omega2 = Eigen::VectorXd::Constant(1, std::pow(2 * kPi * f_frame, 2));
  cf.damping = Eigen::MatrixXd::Zero(1, 1);
  cf.source = "radial breathing";
  model.effects.push_back(std::make_shared<rig::CarryingFrameFlexibility>(cf));
  const rig::RigSystem rig(model);
  const rig::Linearization lin = rig::linearize(rig);
  EXPECT_NEAR(lin.equilibrium.configuration.eta(0), 0.0, 1e-12);  // vertical rod forces do not load it
  const rig::RigMode& mode = mode_along(lin, 6);
  EXPECT_EQ(mode.kind, rig::RigModeKind::deformation);
  const double f_expected = std::sqrt(cf.omega2(0) + W * s * s / l) / (2 * kPi);
  EXPECT_NEAR(mode.frequency_hz, f_expected, 1e-5 * f_expected);
  EXPECT_GT(mode.frequency_hz, f_frame * 1.004);  // +0.5 %: measurably above the free frame's 5 Hz
  record("mode_hz_measured_expected", {mode.frequency_hz, f_expected});
}
