#pragma once
// Two effects compared by what they do: the rig each builds, the loads each
// adds on one moving state and the sensor sample each measures. The
// catalogue's round trips (tests/rig/test_effect_kinds.cpp,
// tests/io/test_effects_yaml.cpp) use it: effects expose no parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rig/effect.hpp"
#include "rig/effect_kinds.hpp"

namespace rigflex::test {

inline void expect_close(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double rel, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  if (a.size() == 0) return;
  const double scale = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), 1e-300});
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), rel * scale) << what;
}

inline Eigen::MatrixXd stacked(const std::vector<rig::Vec3>& v) {
  Eigen::MatrixXd m(3, static_cast<Eigen::Index>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = v[i];
  return m;
}

inline rig::RigAssembly built(const rig::Effect& e, const rig::RigModel& model) {
  rig::RigAssembly a;
  a.geometry = model.geometry;
  a.body = model.body;
  e.build(a);
  return a;
}

// One moving state of the rig: every rod swinging, the body translating and turning.
inline rig::Kinematics moving(const rig::RigGeometry& g) {
  rig::Kinematics k;
  k.R = Eigen::Matrix3d::Identity();
  k.r = g.reference_point;
  k.v = rig::Vec3(0.1, -0.05, 0.01);
  k.omega = rig::Vec3(0.02, 0.01, 0.03);
  k.cog = k.r + rig::Vec3(0.01, 0.0, -0.1);
  for (size_t i = 0; i < g.rods.size(); ++i) {
    rig::RodKinematics r;
    r.A = g.rods[i].upper;
    r.B = g.rods[i].lower;
    r.length = (r.B - r.A).norm();
    r.u = (r.B - r.A) / r.length;
    r.u_rate = rig::Vec3(0.05 * (1.0 + static_cast<double>(i)), -0.03, 0.0);
    r.vA = rig::Vec3::Zero();
    r.vB = k.v;
    r.lower_c = r.B;
    k.rods.push_back(r);
  }
  return k;
}

inline void expect_same_action(const rig::Effect& a, const rig::Effect& b, const rig::RigModel& model, double rel) {
  const std::string name = a.name();
  EXPECT_EQ(name, std::string(b.name()));
  const rig::RigAssembly A = built(a, model), B = built(b, model);
  for (size_t i = 0; i < A.geometry.rods.size(); ++i) {
    expect_close(A.geometry.rods[i].upper, B.geometry.rods[i].upper, rel, name + " upper");
    expect_close(A.geometry.rods[i].lower, B.geometry.rods[i].lower, rel, name + " lower");
    EXPECT_NEAR(A.geometry.rods[i].length, B.geometry.rods[i].length, rel) << name;
  }
  auto vec = [](const std::vector<double>& v) { return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()))); };
  expect_close(vec(A.rod_stiffness), vec(B.rod_stiffness), rel, name + " rod stiffness");
  expect_close(vec(A.rod_mass), vec(B.rod_mass), rel, name + " rod mass");
  ASSERT_EQ(A.fixed_frame.has_value(), B.fixed_frame.has_value()) << name;
  if (A.fixed_frame) {
    expect_close(A.fixed_frame->K, B.fixed_frame->K, rel, name + " K");
    expect_close(A.fixed_frame->M, B.fixed_frame->M, rel, name + " M");
  }
  ASSERT_EQ(A.carrying_frame.has_value(), B.carrying_frame.has_value()) << name;
  if (A.carrying_frame) {
    expect_close(A.carrying_frame->omega2, B.carrying_frame->omega2, rel, name + " omega2");
    expect_close(A.carrying_frame->psi.cwiseAbs(), B.carrying_frame->psi.cwiseAbs(), rel, name + " psi");
  }
  const int n = model.geometry.rod_count();
  const rig::Kinematics k = moving(model.geometry);
  rig::Loads la, lb;
  la.reset(n);
  lb.reset(n);
  a.add_loads(k, la);
  b.add_loads(k, lb);
  expect_close(la.body_force, lb.body_force, rel, name + " body force");
  expect_close(la.body_moment, lb.body_moment, rel, name + " body moment");
  expect_close(stacked(la.lower_force), stacked(lb.lower_force), rel, name + " lower force");
  expect_close(stacked(la.upper_force), stacked(lb.upper_force), rel, name + " upper force");
  rig::SensorSample sa;
  sa.force = Eigen::VectorXd::Constant(n, 327.0);
  sa.alpha = Eigen::VectorXd::Constant(n, 0.01);
  sa.beta = Eigen::VectorXd::Constant(n, -0.02);
  rig::SensorSample sb = sa;
  a.measure(sa);
  b.measure(sb);
  expect_close(sa.force, sb.force, rel, name + " force");
  expect_close(sa.alpha, sb.alpha, rel, name + " alpha");
  expect_close(sa.beta, sb.beta, rel, name + " beta");
}

// A fit context for a rig of rods of about 1 m at about 0.4 m.
inline rig::FitContext fit_context(const rig::RigModel& m) {
  rig::FitContext c;
  c.geometry = m.geometry;
  c.rods = m.geometry.rod_count();
  c.suspended_mass = c.body_mass = m.body.mass;
  c.weight_per_rod = m.body.mass * m.geometry.gravity / c.rods;
  c.rod_length = 1.0;
  c.swing_omega = 2.0 * 3.141592653589793 * 0.5;
  c.joint_radius = 0.4;
  c.rod_stiffness = m.rods.stiffness;
  return c;
}

// Parameter values of every sign and size a fit may end at: the probes, varied.
inline Eigen::VectorXd sample_values(const rig::EffectFitting& f) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(f.parameters.size()));
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    x(k) = f.parameters[k].probe * (1.0 + 0.37 * static_cast<double>(k));
    if (!f.parameters[k].non_negative && k % 2) x(k) = -x(k);
  }
  return x;
}

}  // namespace rigflex::test
