// The body's mass properties as fit parameters (diagnose/body_parameters.hpp):
// which components are fitted, their priors and probes, and that an offset
// lands on the component it names.
#include <gtest/gtest.h>

#include <cmath>

#include "diagnose/body_parameters.hpp"
#include "rig/rig_system.hpp"
#include "support/rig_cases.hpp"

namespace rigflex {
namespace {

TEST(BodyParameters, AllNineWithTheRigFilesUncertainty) {
  rig::RigModel m = test::noisy_trifilar();
  m.body_uncertainty.cog = rig::Vec3(0.001, 0.002, 0.004);
  m.body_uncertainty.inertia = std::array<double, 6>{1, 2, 3, 4, 5, 6};
  const diagnose::BodyParameters p = diagnose::body_parameters(m);
  ASSERT_EQ(p.size(), 9);
  const std::vector<std::string> names{"cog_x", "cog_y", "cog_z", "Jxx", "Jyy", "Jzz", "Jxy", "Jxz", "Jyz"};
  const Eigen::VectorXd sigma = (Eigen::VectorXd(9) << 0.001, 0.002, 0.004, 1, 2, 3, 4, 5, 6).finished();
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(p.components[k], k);
    EXPECT_EQ(p.parameters[k].name, names[k]);
    EXPECT_EQ(p.parameters[k].unit, k < 3 ? "m" : "kg m^2");
    EXPECT_EQ(p.sigma(k), sigma(k));
    // The plausible range is the prior's +-3 sigma; the probe lies well inside one sigma
    // for the CoG (0.2 mm against 1 mm and more).
    EXPECT_EQ(p.parameters[k].high, 3 * sigma(k));
    EXPECT_EQ(p.parameters[k].low, -3 * sigma(k));
    EXPECT_GT(p.parameters[k].probe, 0.0);
  }
  EXPECT_LT(p.parameters[0].probe, p.sigma(0));
}

TEST(BodyParameters, AZeroUncertaintyHoldsTheComponent) {
  rig::RigModel m = test::noisy_trifilar();
  m.body_uncertainty.cog = rig::Vec3(0.003, 0.0, 0.007);
  m.body_uncertainty.inertia = std::array<double, 6>{1, 1, 1, 0, 0, 0};
  const diagnose::BodyParameters p = diagnose::body_parameters(m);
  EXPECT_EQ(p.components, (std::vector<int>{0, 2, 3, 4, 5}));
  // The offsets land on the components named: x and z of the CoG, the principal moments.
  const Eigen::VectorXd delta = (Eigen::VectorXd(5) << 0.001, -0.002, 0.5, 0.25, -0.125).finished();
  const fe::MassProperties b = diagnose::body_with(m.body, p, delta);
  EXPECT_EQ(b.mass, m.body.mass);
  EXPECT_DOUBLE_EQ(b.cog.x(), m.body.cog.x() + 0.001);
  EXPECT_DOUBLE_EQ(b.cog.y(), m.body.cog.y());
  EXPECT_DOUBLE_EQ(b.cog.z(), m.body.cog.z() - 0.002);
  Eigen::Matrix3d dJ = Eigen::Matrix3d::Zero();
  dJ.diagonal() << 0.5, 0.25, -0.125;
  EXPECT_LT((b.inertia - m.body.inertia - dJ).norm(), 1e-12 * m.body.inertia.norm());
}

TEST(BodyParameters, ProductsOfInertiaGoOffTheDiagonalSymmetrically) {
  rig::RigModel m = test::noisy_trifilar();
  m.body_uncertainty.cog = rig::Vec3::Zero();
  m.body_uncertainty.inertia = std::array<double, 6>{0, 0, 0, 1, 1, 1};
  const diagnose::BodyParameters p = diagnose::body_parameters(m);
  ASSERT_EQ(p.components, (std::vector<int>{6, 7, 8}));
  const fe::MassProperties b = diagnose::body_with(m.body, p, Eigen::Vector3d(0.1, 0.2, 0.3));
  // [Jxx Jyy Jzz Jxy Jxz Jyz] as the rig file writes them: Jxy at (0, 1) and (1, 0), and so on.
  const Eigen::Matrix3d dJ = b.inertia - m.body.inertia;
  EXPECT_NEAR(dJ(0, 1), 0.1, 1e-12);
  EXPECT_NEAR(dJ(1, 0), 0.1, 1e-12);
  EXPECT_NEAR(dJ(0, 2), 0.2, 1e-12);
  EXPECT_NEAR(dJ(2, 0), 0.2, 1e-12);
  EXPECT_NEAR(dJ(1, 2), 0.3, 1e-12);
  EXPECT_NEAR(dJ(2, 1), 0.3, 1e-12);
  EXPECT_NEAR(dJ.diagonal().norm(), 0.0, 1e-12);
}

// Where the rig file states how well it knows the rods' stiffness, one
// common factor on it is fitted after the body: an offset in %, its prior
// the stated relative uncertainty; rigid rods have none.
TEST(BodyParameters, TheRodsStiffnessWhereItsUncertaintyIsStated) {
  rig::RigModel m = test::noisy_trifilar();
  m.body_uncertainty.cog = rig::Vec3(0.003, 0.0, 0.0);
  m.body_uncertainty.inertia = std::array<double, 6>{0, 0, 0, 0, 0, 0};
  m.rods.stiffness = {2e7, 3e7, 4e7};
  EXPECT_EQ(diagnose::body_parameters(m).components, (std::vector<int>{0}));  // no uncertainty stated: held
  m.rods.stiffness_uncertainty = 0.15;
  const diagnose::BodyParameters p = diagnose::body_parameters(m);
  ASSERT_EQ(p.components, (std::vector<int>{0, 9}));
  EXPECT_EQ(p.parameters[1].name, "rods.stiffness");
  EXPECT_EQ(p.parameters[1].unit, "%");
  EXPECT_DOUBLE_EQ(p.sigma(1), 15.0);
  EXPECT_LT(p.parameters[1].probe, p.sigma(1));
  // The offset scales every rod's stiffness by one factor and leaves the body's mass properties alone.
  const rig::RigModel out = diagnose::model_with(m, p, Eigen::Vector2d(0.001, -20.0));
  ASSERT_EQ(out.rods.stiffness.size(), 3u);
  for (size_t i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(out.rods.stiffness[i], 0.8 * m.rods.stiffness[i]);
  EXPECT_DOUBLE_EQ(out.body.cog.x(), m.body.cog.x() + 0.001);
  EXPECT_EQ(out.body.inertia, m.body.inertia);
  // Rigid rods have no stiffness to refit.
  m.rods.stiffness.clear();
  EXPECT_EQ(diagnose::body_parameters(m).components, (std::vector<int>{0}));
}

// An effect in the model whose uncertainty the rig file states: one fitted
// component per item, after the body's, named after the effect and key;
// the offset rebuilds the effect with the moved value, other effects and
// the body untouched.
TEST(BodyParameters, AnEffectsParametersWhereTheirUncertaintyIsStated) {
  using V = rig::ParameterValue;
  rig::RigModel m = test::noisy_trifilar();
  m.body_uncertainty.cog = rig::Vec3(0.003, 0.0, 0.0);
  m.body_uncertainty.inertia = std::array<double, 6>{0, 0, 0, 0, 0, 0};
  test::add_effect(m, "rod_mass",
                   V::map().set("mass", V::of(2.0)).set("uncertainty", V::map().set("mass", V::of(0.5))));
  const diagnose::BodyParameters p = diagnose::body_parameters(m);
  ASSERT_EQ(p.components, (std::vector<int>{0, diagnose::BodyParameters::kEffectItems}));
  EXPECT_EQ(p.parameters[1].name, "effects.rod_mass.mass");
  EXPECT_EQ(p.parameters[1].unit, "kg");
  EXPECT_DOUBLE_EQ(p.sigma(1), 0.5);
  EXPECT_LT(p.parameters[1].probe, p.sigma(1));
  const rig::RigModel out = diagnose::model_with(m, p, Eigen::Vector2d(0.0, 0.75));
  ASSERT_EQ(out.effects.size(), 1u);
  const rig::RigSystem moved(out), held(m);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(moved.assembly().rod_mass[static_cast<size_t>(i)], 2.75);
    EXPECT_DOUBLE_EQ(held.assembly().rod_mass[static_cast<size_t>(i)], 2.0);
  }
  EXPECT_EQ(out.body.cog, m.body.cog);
}

// A frame that states how well its stiffness is known: one component, a
// factor on the built frame's stiffness in %, which moves K by that factor
// and its damping by the factor's root (each mode's damping ratio kept),
// and leaves its mass, the body and the rods as they were.
TEST(BodyParameters, AFramesStiffnessWhereItsUncertaintyIsStated) {
  using V = rig::ParameterValue;
  rig::RigModel m = test::noisy_trifilar();
  m.body_uncertainty.cog = rig::Vec3(0.003, 0.0, 0.0);
  m.body_uncertainty.inertia = std::array<double, 6>{0, 0, 0, 0, 0, 0};
  const V joint = V::of(std::vector<double>{1e-7, 1e-7, 1e-8});
  test::add_effect(m, "fixed_frame_flexibility",
                   V::map()
                       .set("joint_compliance", V::map().set("joints", V::list({joint, joint, joint})))
                       .set("uncertainty", V::map().set("stiffness", V::of(0.2))));
  const diagnose::BodyParameters p = diagnose::body_parameters(m);
  ASSERT_EQ(p.components, (std::vector<int>{0, diagnose::BodyParameters::kEffectItems}));
  EXPECT_EQ(p.parameters[1].name, "effects.fixed_frame_flexibility.stiffness");
  EXPECT_EQ(p.parameters[1].unit, "%");
  EXPECT_DOUBLE_EQ(p.sigma(1), 20.0);
  const rig::RigModel out = diagnose::model_with(m, p, Eigen::Vector2d(0.0, -25.0));
  ASSERT_EQ(out.effects.size(), 1u);
  const rig::RigSystem moved(out), held(m);
  const rig::FixedFrameModel& a = *moved.assembly().fixed_frame;
  const rig::FixedFrameModel& b = *held.assembly().fixed_frame;
  EXPECT_TRUE(a.K.isApprox(0.75 * b.K, 1e-14));
  EXPECT_EQ(a.M, b.M);
  EXPECT_TRUE(a.C.isApprox(std::sqrt(0.75) * b.C, 1e-14));
  EXPECT_EQ(out.body.cog, m.body.cog);
  // Nothing moved: the model's own frame, not a copy scaled by 1.
  EXPECT_EQ(diagnose::model_with(m, p, Eigen::Vector2d(0.001, 0.0)).effects.front(), m.effects.front());
}

}  // namespace
}  // namespace rigflex
