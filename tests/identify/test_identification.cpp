// The identifier (identify/identification.hpp) on data with known answers:
// analytic rigid-body motion with Newton-Euler loads (exact to rounding),
// the point fit, tare subtraction, unobservable records, the rod-mass
// accounting at static equilibrium; virtual measurements of the example rigs
// are in tests/acceptance.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include "rig/effects.hpp"
#include "rig/equilibrium.hpp"
#include "identify/identification.hpp"
#include "rig/simulation.hpp"
#include "identify/mass_statistics.hpp"
#include "rig/pose_fit.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;
using rig::Vec3;
using Mat3 = Eigen::Matrix3d;

template <class T>
Eigen::Matrix<T, 3, 3> rotation(const Vec3& axis, T angle) {
  const Eigen::Matrix<T, 3, 1> a = axis.normalized().cast<T>();
  Eigen::Matrix<T, 3, 3> K;
  K << T(0), -a.z(), a.y(), a.z(), T(0), -a.x(), -a.y(), a.x(), T(0);
  return Eigen::Matrix<T, 3, 3>::Identity() + std::sin(angle) * K + (T(1) - std::cos(angle)) * K * K;
}

// A swing-like analytic motion: P and three successive rotations about fixed
// axes, each a sum of two sinusoids at pendulum frequencies (0.55-1.9 Hz).
struct AnalyticMotion {
  Vec3 P0{0.1, -0.05, 2.55};
  std::array<Vec3, 3> axes{Vec3(0, 0, 1), Vec3(0.2, 1, 0), Vec3(1, 0, 0.1)};

  template <class T>
  T angle(int k, T t, int d) const {  // d-th derivative of angle k
    const double amp[3][2] = {{0.04, 0.01}, {0.05, 0.008}, {0.03, 0.012}};
    const double f[3][2] = {{1.9, 0.55}, {0.62, 1.3}, {0.71, 1.1}};
    T s = T(0);
    for (int j = 0; j < 2; ++j) {
      const double w = 2 * std::numbers::pi * f[k][j];
      const T arg = w * t + (0.3 * (k + 1) + j);
      const T v = d == 0 ? std::sin(arg) : d == 1 ? w * std::cos(arg) : -w * w * std::sin(arg);
      s += amp[k][j] * v;
    }
    return s;
  }
  Vec3 position(double t, int d) const {
    const double f[3] = {0.6, 0.66, 1.25}, amp[3] = {0.05, 0.04, 0.002};
    Vec3 r = d == 0 ? P0 : Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      const double w = 2 * std::numbers::pi * f[i], arg = w * t + i;
      r(i) += amp[i] * (d == 0 ? std::sin(arg) : d == 1 ? w * std::cos(arg) : -w * w * std::sin(arg));
    }
    return r;
  }
  template <class T>
  Eigen::Matrix<T, 3, 3> R(T t) const {
    return rotation(axes[0], angle(0, t, 0)) * rotation(axes[1], angle(1, t, 0)) * rotation(axes[2], angle(2, t, 0));
  }
  // Angular velocity in frame c of R = R0 R1 R2: R2' R1' e0 q0' + R2' e1 q1' + e2 q2'.
  template <class T>
  Eigen::Matrix<T, 3, 1> omega_c(T t) const {
    const auto R1 = rotation(axes[1], angle(1, t, 0));
    const auto R2 = rotation(axes[2], angle(2, t, 0));
    return R2.transpose() * R1.transpose() * axes[0].normalized().cast<T>() * angle(0, t, 1) +
           R2.transpose() * axes[1].normalized().cast<T>() * angle(1, t, 1) +
           axes[2].normalized().cast<T>() * angle(2, t, 1);
  }
  // Its derivative by the complex step: exact to rounding, no subtraction.
  Vec3 alpha_c(double t) const {
    const double h = 1e-20;
    const Eigen::Matrix<std::complex<double>, 3, 1> w = omega_c(std::complex<double>(t, h));
    return Vec3(w(0).imag(), w(1).imag(), w(2).imag()) / h;
  }
};

struct Truth {
  double m = 2914.0;
  Vec3 c{0.511, -0.008, -0.598};
  Mat3 J_P;  // about P
};

Truth reference_body() {
  Truth b;
  Mat3 J_G;
  J_G << 1632, 44, -483, 44, 5729, 4, -483, 4, 5510;
  b.J_P = J_G + b.m * (b.c.squaredNorm() * Mat3::Identity() - b.c * b.c.transpose());
  return b;
}

identify::IdentificationRig three_rod_rig(double mass) {
  identify::IdentificationRig r;
  r.mass = mass;
  r.geometry.gravity = 9.80665;
  for (const Vec3& b : {Vec3(1.2, -1.4, 0), Vec3(-1.2, -1.4, 0), Vec3(0, 1.4, 0)}) {
    rig::RodGeometry rod;
    rod.lower = b;
    rod.upper = b + Vec3(0, 0, 3.15);
    rod.length = 0.6;
    r.geometry.rods.push_back(rod);
  }
  r.rod_mass = Eigen::VectorXd::Zero(3);
  return r;
}

// Joints, resultant and moment about G's origin of the Newton-Euler loads
// that produce the analytic motion, sampled at fs for `duration`.
identify::MotionSeries exact_series(const identify::IdentificationRig& rig, const Truth& body, const AnalyticMotion& mo,
                               double fs, double duration, double t0 = 0.0) {
  const auto S = static_cast<Eigen::Index>(std::lround(duration * fs)) + 1;
  identify::MotionSeries s;
  s.t.resize(S);
  s.joints.resize(S, 9);
  s.force.resize(S, 3);
  s.moment.resize(S, 3);
  const Vec3 g(0, 0, -rig.geometry.gravity);
  for (Eigen::Index k = 0; k < S; ++k) {
    const double t = t0 + static_cast<double>(k) / fs;
    s.t(k) = t;
    const Mat3 R = mo.R(t);
    const Vec3 r = mo.position(t, 0);
    const Vec3 a = R.transpose() * mo.position(t, 2), w = mo.omega_c(t), dw = mo.alpha_c(t);
    const Vec3 gc = R.transpose() * g;
    const Vec3 F = body.m * (a + dw.cross(body.c) + w.cross(w.cross(body.c))) - body.m * gc;
    const Vec3 M = body.J_P * dw + w.cross(body.J_P * w) + body.m * body.c.cross(a - gc);
    for (int i = 0; i < 3; ++i) s.joints.block<1, 3>(k, 3 * i) = (r + R * rig.geometry.rods[i].lower).transpose();
    s.force.row(k) = (R * F).transpose();
    s.moment.row(k) = (r.cross(R * F) + R * M).transpose();
  }
  return s;
}

// Error of each identified parameter relative to its scale: |c| for the
// CoG, the largest moment for the inertia.
std::array<double, 9> relative_errors(const identify::IdentificationResult& r, const Truth& b) {
  std::array<double, 9> e{};
  const double cs = b.c.norm(), js = b.J_P.diagonal().maxCoeff();
  for (int i = 0; i < 3; ++i) e[static_cast<size_t>(i)] = std::abs(r.properties.cog(i) - b.c(i)) / cs;
  const int idx[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  for (int q = 0; q < 6; ++q) {
    e[static_cast<size_t>(3 + q)] = std::abs(r.inertia_about_P(idx[q][0], idx[q][1]) - b.J_P(idx[q][0], idx[q][1])) / js;
  }
  return e;
}

// Every parameter within 1e-8 of its scale (the exact-data tolerance).
void expect_recovered_to_1e8(const identify::IdentificationResult& r, const Truth& b) {
  ASSERT_TRUE(r.observable) << r.message;
  const auto e = relative_errors(r, b);
  for (size_t i = 0; i < 9; ++i) EXPECT_LT(e[i], 1e-8) << identify::mass_component_names()[i];
}

// Short, high-degree kernels: their bias at 1.9 Hz, (omega T)^10-ish, is far
// below 1e-12, so what remains is rounding.
identify::IdentificationOptions exact_options() {
  identify::IdentificationOptions o;
  o.differentiation.window_s = 0.05;
  o.differentiation.degree = 8;
  return o;
}

TEST(IdentificationExact, AnalyticMotionRecoversAllNineParametersTo1e8) {
  const Truth body = reference_body();
  const AnalyticMotion motion;
  const auto rig = three_rod_rig(body.m);
  const identify::IdentificationOptions o = exact_options();
  // Precondition of the tolerance: the kernel's bias at the fastest frequency.
  const auto k = identify::savitzky_golay_kernels(o.differentiation, 1.0 / 500);
  ASSERT_LT(std::abs(identify::savitzky_golay_gain(k, 2, 1.9) - 1.0), 1e-11);

  const auto samples = identify::equation_samples(rig, exact_series(rig, body, motion, 500, 15), o);
  const auto r = identify::solve_mass_properties(samples, body.m, {}, 9.80665, 1.5, o);
  expect_recovered_to_1e8(r, body);
  double worst_pose = 0;
  for (const auto& e : samples) worst_pose = std::max(worst_pose, e.pose_residual);
  EXPECT_LT(worst_pose, 1e-12);
  EXPECT_TRUE(r.positive_definite);
  EXPECT_TRUE(r.triangle_inequality);
  // The CoG inertia is the transfer of the P inertia.
  const Mat3 back = r.properties.inertia + body.m * (r.properties.cog.squaredNorm() * Mat3::Identity() -
                                                     r.properties.cog * r.properties.cog.transpose());
  EXPECT_LT((back - r.inertia_about_P).norm(), 1e-9 * r.inertia_about_P.norm());
}

TEST(IdentificationExact, ImposedCogGivesTheSameInertia) {
  const Truth body = reference_body();
  const auto rig = three_rod_rig(body.m);
  const auto samples = identify::equation_samples(rig, exact_series(rig, body, AnalyticMotion{}, 500, 10), exact_options());
  for (auto c : {identify::CogConstraint::in_plane, identify::CogConstraint::full}) {
    identify::IdentificationOptions o = exact_options();
    o.cog_constraint = c;
    o.imposed_cog = body.c;
    const auto r = identify::solve_mass_properties(samples, body.m, {}, 9.80665, 1.5, o);
    expect_recovered_to_1e8(r, body);
    // Imposed components come back exactly as given.
    EXPECT_EQ(r.properties.cog.x(), body.c.x());
    EXPECT_EQ(r.properties.cog.y(), body.c.y());
    if (c == identify::CogConstraint::full) {
      EXPECT_EQ(r.properties.cog.z(), body.c.z());
    }
  }
}

TEST(IdentificationExact, RodPointMassesAreTakenOutOfTheResult) {
  // The identified system carries known point masses at the joints: the
  // loads are those of body + points, the result must be the body alone.
  const Truth body = reference_body();
  auto rig = three_rod_rig(body.m);
  Truth with = body;
  std::vector<std::pair<double, Vec3>> points;
  Vec3 S = body.m * body.c;
  for (int i = 0; i < 3; ++i) {
    const double mi = 2.0 + i;
    const Vec3 b = rig.geometry.rods[i].lower;
    points.emplace_back(mi, b);
    with.m += mi;
    S += mi * b;
    with.J_P += mi * (b.squaredNorm() * Mat3::Identity() - b * b.transpose());
  }
  with.c = S / with.m;
  const auto samples = identify::equation_samples(rig, exact_series(rig, with, AnalyticMotion{}, 500, 10), exact_options());
  const auto r = identify::solve_mass_properties(samples, body.m, points, 9.80665, 1.5, exact_options());
  expect_recovered_to_1e8(r, body);
}

TEST(IdentificationExact, StillRecordIsNotObservableAndNamesTheParameters) {
  // Hanging at rest: the weight's moment fixes xG and yG; nothing fixes zG
  // (parallel to gravity) or the inertia.
  const Truth body = reference_body();
  const auto rig = three_rod_rig(body.m);
  identify::MotionSeries s = exact_series(rig, body, AnalyticMotion{}, 500, 3);
  for (Eigen::Index k = 0; k < s.t.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      s.joints.block<1, 3>(k, 3 * i) = (Vec3(0, 0, 2.55) + rig.geometry.rods[i].lower).transpose();
    }
    s.force.row(k) = Vec3(0, 0, body.m * 9.80665).transpose();
    s.moment.row(k) = -(Vec3(0, 0, 2.55) + body.c).cross(Vec3(0, 0, -body.m * 9.80665)).transpose();
  }
  const auto samples = identify::equation_samples(rig, s, identify::IdentificationOptions{});
  const auto r = identify::solve_mass_properties(samples, body.m, {}, 9.80665, 1.5, identify::IdentificationOptions{});
  EXPECT_FALSE(r.observable);
  auto has = [&](const std::string& n) {
    return std::find(r.unobservable.begin(), r.unobservable.end(), n) != r.unobservable.end();
  };
  EXPECT_TRUE(has("zG")) << r.message;
  EXPECT_TRUE(has("Jxx")) << r.message;
  EXPECT_TRUE(has("Jzz")) << r.message;
  EXPECT_FALSE(has("xG")) << r.message;
  EXPECT_NE(r.message.find("not observable"), std::string::npos);
  // Both causes are named, with the residual that tells them apart: here
  // the still record fits exactly, so the residual is round-off.
  EXPECT_NE(r.message.find("larger swings"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("the model does not fit the records"), std::string::npos) << r.message;
  const auto at = r.message.find("equation residual ");
  ASSERT_NE(at, std::string::npos) << r.message;
  EXPECT_LT(std::stod(r.message.substr(at + 18)), 1e-6) << r.message;
}

TEST(IdentificationExact, RecordShorterThanTheWindowIsReportedNotSolved) {
  const Truth body = reference_body();
  const auto rig = three_rod_rig(body.m);
  const auto samples = identify::equation_samples(rig, exact_series(rig, body, AnalyticMotion{}, 500, 0.1), {});
  const auto r = identify::solve_mass_properties(samples, body.m, {}, 9.80665, 1.5, {});
  EXPECT_FALSE(r.observable);
  EXPECT_NE(r.message.find("shorter than the differentiation window"), std::string::npos) << r.message;
}

TEST(IdentificationExact, DroppedSampleSplitsTheRecordWithoutBias) {
  // A missing sample must not enter any differentiation window.
  const Truth body = reference_body();
  const auto rig = three_rod_rig(body.m);
  identify::MotionSeries s = exact_series(rig, body, AnalyticMotion{}, 500, 10);
  const Eigen::Index drop = 2345, S = s.t.size();
  auto remove = [&](auto& m) {
    auto copy = m;
    m.resize(S - 1, m.cols());
    m.topRows(drop) = copy.topRows(drop);
    m.bottomRows(S - 1 - drop) = copy.bottomRows(S - 1 - drop);
  };
  Eigen::VectorXd t(S - 1);
  t << s.t.head(drop), s.t.tail(S - 1 - drop);
  s.t = t;
  remove(s.joints);
  remove(s.force);
  remove(s.moment);
  const auto r = identify::solve_mass_properties(identify::equation_samples(rig, s, exact_options()), body.m, {}, 9.80665, 1.5,
                                            exact_options());
  expect_recovered_to_1e8(r, body);
}

TEST(IdentificationExact, TimeStampsRoundedByTheLoggerDoNotSplitTheRecord) {
  // 300 Hz stamped in whole milliseconds: steps of 3 and 4 ms over a uniform
  // clock. The samples are uniform, so the answer is as exact as unrounded.
  const Truth body = reference_body();
  const auto rig = three_rod_rig(body.m);
  identify::MotionSeries s = exact_series(rig, body, AnalyticMotion{}, 300, 10);
  s.t = (s.t * 1000.0).array().round() / 1000.0;
  const auto samples = identify::equation_samples(rig, s, exact_options());
  ASSERT_GT(samples.size(), 400u);  // 50 per second over 10 s, less the window's edges
  const auto r = identify::solve_mass_properties(samples, body.m, {}, 9.80665, 1.5, exact_options());
  expect_recovered_to_1e8(r, body);
}

TEST(IdentificationRodMass, HeavyRodsAtRestLeaveTheSystemsWeightAndItsMoment) {
  // At rest the loads on the identified system (the record plus each rod's
  // moving third at its lower joint) must be its weight at its CoG. Rods of
  // 30 kg on a 100 kg disk with an offset CoG, read by the simulator's load
  // cells (upper rod end: spring force plus half the rod's weight along it)
  // at the simulator's equilibrium: an error in the half/third accounting
  // shows at the 10 N level. Tolerance: the equilibrium's residual (1e-9 of
  // the weight) and rounding.
  rig::RigModel model = test::multifilar_rig(3, 0.4, 1.0, 100.0, 0.5, 0.1);
  model.body.cog = Vec3(0.05, -0.03, -0.1);
  model.effects.push_back(std::make_shared<rig::RodMass>(std::vector<double>{30.0, 25.0, 35.0}));
  const rig::RigSystem sys(model);
  const rig::Equilibrium eq = rig::static_equilibrium(sys);
  ASSERT_TRUE(eq.converged) << eq.message;
  const rig::SensorSample s = rig::read_sensors(sys, eq.configuration, sys.at_rest(), 0.0);
  rig::Record record;
  record.t = Eigen::VectorXd::LinSpaced(2, 0.0, 0.002);
  record.force = s.force.transpose().replicate(2, 1);
  record.alpha = s.alpha.transpose().replicate(2, 1);
  record.beta = s.beta.transpose().replicate(2, 1);
  const identify::IdentificationRig idr = identify::identification_rig(model, identify::IdentificationAlgorithm::rigid);
  const identify::MotionSeries m = identify::motion_series(idr, record);

  double m_id = model.body.mass;
  Vec3 first_moment = model.body.mass * model.body.cog;
  for (int i = 0; i < 3; ++i) {
    m_id += idr.rod_mass(i) / 3.0;
    first_moment += idr.rod_mass(i) / 3.0 * model.geometry.rods[i].lower;
  }
  const double g = model.geometry.gravity;
  const Vec3 F = m.force.row(0).transpose();
  EXPECT_LT((F - Vec3(0, 0, m_id * g)).norm(), 1e-8 * m_id * g) << F.transpose();
  // About P (the pose is the equilibrium's, rotation ~1e-12 here): the
  // rods balance the weight's moment, -(R S) x (m_id g).
  const Mat3 R = eq.configuration.q.toRotationMatrix();
  const Vec3 M_P = m.moment.row(0).transpose() - eq.configuration.r.cross(F);
  const Vec3 expected = -(R * first_moment).cross(Vec3(0, 0, -g));
  EXPECT_LT((M_P - expected).norm(), 1e-8 * m_id * g) << M_P.transpose() << " vs " << expected.transpose();
}

TEST(IdentificationPoseFit, RecoversRandomPosesExactlyAndReportsInconsistency) {
  std::mt19937_64 gen(7);
  std::normal_distribution<double> n01;
  for (int n : {3, 4}) {
    rig::JointPoints b(3, n), B(3, n);
    for (int i = 0; i < n; ++i) b.col(i) = Vec3(n01(gen), n01(gen), i == 3 ? 0.3 : 0.0);
    for (int trial = 0; trial < 20; ++trial) {
      const Mat3 R = Eigen::Quaterniond(n01(gen), n01(gen), n01(gen), n01(gen)).normalized().toRotationMatrix();
      const Vec3 r(n01(gen), n01(gen), n01(gen));
      for (int i = 0; i < n; ++i) B.col(i) = r + R * b.col(i);
      const rig::PoseFit f = rig::fit_pose(b, B);
      EXPECT_LT((f.R - R).norm(), 1e-12);
      EXPECT_LT((f.r - r).norm(), 1e-12);
      EXPECT_LT(f.rms_residual, 1e-12);
      EXPECT_NEAR(f.R.determinant(), 1.0, 1e-12);
    }
  }
  // A fourth joint 4 mm out of plane: the best fit shifts by d/4 and tilts
  // by d/4 about both axes of the 2 m square, leaving +-d/4 at every corner,
  // rms d/4 (to second order in d / size: 1e-8 m allowed).
  rig::JointPoints b(3, 4), B(3, 4);
  b << 1, -1, -1, 1, 1, 1, -1, -1, 0, 0, 0, 0;
  B = b;
  B(2, 0) += 0.004;
  const rig::PoseFit f = rig::fit_pose(b, B);
  EXPECT_NEAR(f.rms_residual, 0.004 / 4.0, 1e-8);
  rig::JointPoints line(3, 3);
  line << 0, 1, 2, 0, 0, 0, 0, 0, 0;
  EXPECT_THROW(rig::fit_pose(line, line), std::invalid_argument);
}

TEST(IdentificationTare, SubtractingTheCarryingFrameGivesTheBody) {
  // Two rigid parts: the tare (a frame) and the body; their union is the
  // system. Parallel-axis sums are exact.
  fe::MassProperties tare, body;
  tare.mass = 400;
  tare.cog = Vec3(0.0, 0.02, -0.1);
  tare.inertia << 300, 5, -2, 5, 420, 1, -2, 1, 650;
  body.mass = 2514;
  body.cog = Vec3(0.6, -0.015, -0.68);
  body.inertia << 1300, 30, -400, 30, 4800, 3, -400, 3, 4600;
  auto about_origin = [](const fe::MassProperties& p) { return identify::inertia_about(p, Vec3::Zero()); };
  fe::MassProperties system;
  system.mass = tare.mass + body.mass;
  system.cog = (tare.mass * tare.cog + body.mass * body.cog) / system.mass;
  system.inertia = about_origin(tare) + about_origin(body) -
                   system.mass * (system.cog.squaredNorm() * Mat3::Identity() - system.cog * system.cog.transpose());
  const fe::MassProperties got = identify::subtract_tare(system, tare);
  EXPECT_NEAR(got.mass, body.mass, 1e-9);
  EXPECT_LT((got.cog - body.cog).norm(), 1e-12);
  EXPECT_LT((got.inertia - body.inertia).norm(), 1e-9 * body.inertia.norm());
  EXPECT_THROW(identify::subtract_tare(tare, system), std::invalid_argument);
}

}  // namespace
