// Static equilibrium and the linearized rig against the closed-form
// multifilar pendulums of shared/verification/pendulum_closed_form.yaml.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rig/design_check.hpp"
#include "rig/effects.hpp"
#include "rig/linearization.hpp"
#include "support/rig_cases.hpp"

using namespace rigflex;
using rig::Vec3;

namespace {

std::vector<double> frequencies_of_kind(const rig::Linearization& lin, rig::RigModeKind kind) {
  std::vector<double> f;
  for (const auto& m : lin.modes) {
    if (m.kind == kind) f.push_back(m.frequency_hz);
  }
  return f;
}

}  // namespace

TEST(RigEquilibrium, RodForcesCarryTheWeight) {
  // An off-centre, tilted body: the equilibrium pose rotates and the rods share unequally.
  rig::RigModel model = test::multifilar_rig(4, 0.6, 1.5, 850.0, 0.8, 0.4);
  model.body.cog = Vec3(0.11, -0.07, -0.4);
  model.body.inertia << 180.0, 4.0, -12.0, 4.0, 190.0, 3.0, -12.0, 3.0, 272.0;
  const rig::RigSystem rig(model);
  const rig::Equilibrium eq = rig::static_equilibrium(rig);
  ASSERT_TRUE(eq.converged) << eq.message;
  const rig::Kinematics k = rig.kinematics(eq.configuration, rig.at_rest(), 0.0);
  Vec3 sum = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
  for (const auto& r : k.rods) {
    EXPECT_GT(r.force, 0.0);  // tension positive
    sum += -r.force * r.u;    // force of the rod on the carrying frame
    moment += (r.B - k.cog).cross(-r.force * r.u);
  }
  const double W = 850.0 * 9.81;
  EXPECT_LT(std::abs(sum.z() - W) / W, 1e-9);
  EXPECT_LT(sum.head<2>().norm() / W, 1e-9);
  EXPECT_LT(moment.norm() / (W * 1.5), 1e-9);
}

TEST(RigLinearization, TrifilarMatchesClosedForm) {
  // Disk Rd = 0.5 m on three 1 m threads at R = 0.4 m, CoG in the joint plane:
  // sway 0.498488 Hz (simple pendulum), yaw 0.563975 Hz (pendulum_closed_form.yaml).
  const rig::RigSystem rig(test::multifilar_rig(3, 0.4, 1.0, 100.0, 0.5, 0.0));
  const rig::Linearization lin = rig::linearize(rig);
  EXPECT_LT(lin.asymmetry, 1e-6);
  EXPECT_LT(lin.eigen.residuals.maxCoeff(), 1e-8);
  EXPECT_LT(lin.eigen.orthogonality_error, 1e-10);
  const auto swing = frequencies_of_kind(lin, rig::RigModeKind::swing);
  ASSERT_EQ(swing.size(), 3u);
  // Rigid rods are springs with a 300 Hz bounce: (0.5 / 300)^2 ~ 3e-6 relative error.
  EXPECT_NEAR(swing[0], 0.498488, 0.498488 * 2e-5);
  EXPECT_NEAR(swing[1], 0.498488, 0.498488 * 2e-5);
  EXPECT_NEAR(swing[2], 0.563975, 0.563975 * 2e-5);
  EXPECT_EQ(frequencies_of_kind(lin, rig::RigModeKind::rod_constraint).size(), 3u);
  EXPECT_TRUE(frequencies_of_kind(lin, rig::RigModeKind::deformation).empty());
}

TEST(RigLinearization, QuadrifilarYawAndRodBounce) {
  // Four compliant rods: yaw sqrt(m g R^2 / (I L)) / 2 pi for n threads; bounce sqrt(4 k / m) / 2 pi.
  rig::RigModel model = test::multifilar_rig(4, 0.4, 1.0, 100.0, 0.5, 0.0);
  const double k = 2.0e6;
  model.effects.push_back(std::make_shared<rig::RodCompliance>(std::vector<double>(4, k)));
  const rig::Linearization lin = rig::linearize(rig::RigSystem(model));
  const auto swing = frequencies_of_kind(lin, rig::RigModeKind::swing);
  ASSERT_EQ(swing.size(), 3u);
  // Compliant rods stretch by m g / (4 k) = 1.2e-4 m: the pendulum is that much longer.
  const double stretch = 100.0 * 9.81 / (4 * k);
  EXPECT_NEAR(swing[2], 0.563975 * std::sqrt(1.0 / (1.0 + stretch)), 0.563975 * 2e-5);
  const auto deform = frequencies_of_kind(lin, rig::RigModeKind::deformation);
  ASSERT_FALSE(deform.empty());
  // Bounce: 4 k + the geometric stiffness of nothing (vertical rods) -> sqrt(4 k / m).
  EXPECT_NEAR(deform[0], std::sqrt(4 * k / 100.0) / (2 * std::numbers::pi), 1e-4 * deform[0]);
}
