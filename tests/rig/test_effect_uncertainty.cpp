// An effect's stated uncertainty (rig/effect_uncertainty.hpp): taken out of
// the effect's parameters so that its kind reads them as before, and the
// offsets diagnose fits put back on the right numbers, within the
// parameter's physical range.
#include <gtest/gtest.h>

#include <cmath>

#include "rig/effect_kinds.hpp"
#include "rig/effect_uncertainty.hpp"

using namespace rigflex;

namespace {

using V = rig::ParameterValue;

double number(const V& map, const std::string& key, int rod = -1) {
  const V& v = map[key];
  return rod < 0 ? *v.number : *v.items[static_cast<size_t>(rod)].number;
}

TEST(EffectUncertainty, TakenOutOfTheEffectsParameters) {
  V tree = V::map().set("mass", V::of(1.5)).set("uncertainty", V::map().set("mass", V::of(0.3)));
  const auto u = rig::take_uncertainty(*rig::find_effect_kind("rod_mass"), tree, 3);
  ASSERT_TRUE(u);
  EXPECT_FALSE(tree["uncertainty"].defined());
  EXPECT_FALSE(u->parameters["uncertainty"].defined());
  ASSERT_EQ(u->items.size(), 1u);
  EXPECT_EQ(u->items[0].sigma, 0.3);
  EXPECT_EQ(u->items[0].unit, "kg");
  // Without an uncertainty: none, the tree untouched.
  V plain = V::map().set("mass", V::of(1.5));
  EXPECT_FALSE(rig::take_uncertainty(*rig::find_effect_kind("rod_mass"), plain, 3));
  EXPECT_EQ(plain, V::map().set("mass", V::of(1.5)));
}

// A common offset moves every rod's value; a per-rod one moves its rod's
// only (one value for all rods becomes a list); a key the file leaves at
// its default is offset from the default.
TEST(EffectUncertainty, OffsetsGoOnTheirNumbers) {
  V tree = V::map()
               .set("offset", V::of(std::vector<double>{1.0, 2.0, 3.0}))
               .set("uncertainty",
                    V::map().set("offset", V::of(0.5)).set("gain", V::of(std::vector<double>{0.01, 0.01, 0.01})));
  const auto u = rig::take_uncertainty(*rig::find_effect_kind("load_cell_gain"), tree, 3);
  ASSERT_TRUE(u);
  ASSERT_EQ(u->items.size(), 4u);
  Eigen::Vector4d d(0.25, 0.02, 0.0, -0.03);
  const V p = rig::with_offsets(*u, d);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(number(p, "offset", i), 1.0 + i + 0.25);
  EXPECT_DOUBLE_EQ(number(p, "gain", 0), 1.02);  // the default gain, 1
  EXPECT_DOUBLE_EQ(number(p, "gain", 1), 1.0);
  EXPECT_DOUBLE_EQ(number(p, "gain", 2), 0.97);
  // The kind reads the result.
  rig::EffectParseContext x;
  x.key = "effects.load_cell_gain";
  x.rods = 3;
  EXPECT_NO_THROW(rig::find_effect_kind("load_cell_gain")->parse(p, x));

  V masses = V::map()
                 .set("mass", V::of(2.0))
                 .set("uncertainty", V::map().set("mass", V::of(std::vector<double>{0.1, 0.2, 0.3})));
  const auto m = rig::take_uncertainty(*rig::find_effect_kind("rod_mass"), masses, 3);
  const V q = rig::with_offsets(*m, Eigen::Vector3d(0.0, 0.5, 0.0));
  ASSERT_EQ(q["mass"].kind, V::Kind::list);
  EXPECT_DOUBLE_EQ(number(q, "mass", 0), 2.0);
  EXPECT_DOUBLE_EQ(number(q, "mass", 1), 2.5);
  EXPECT_DOUBLE_EQ(number(q, "mass", 2), 2.0);
}

// A fit that asks for less than nothing, or more than the rig allows, gets
// the range's edge: a mass of 0, a gain of 0.5, a rod mass of the body's
// mass where the rig's scales are known - and no upper edge where they are
// not.
TEST(EffectUncertainty, OffsetsStayWithinThePhysicalRange) {
  V masses = V::map().set("mass", V::of(2.0)).set("uncertainty", V::map().set("mass", V::of(1.0)));
  const auto m = rig::take_uncertainty(*rig::find_effect_kind("rod_mass"), masses, 3);
  EXPECT_EQ(number(rig::with_offsets(*m, Eigen::VectorXd::Constant(1, -5.0)), "mass"), 0.0);
  EXPECT_EQ(number(rig::with_offsets(*m, Eigen::VectorXd::Constant(1, 50.0)), "mass"), 52.0);
  V gains = V::map().set("gain", V::of(1.0)).set("uncertainty", V::map().set("gain", V::of(0.1)));
  const auto g = rig::take_uncertainty(*rig::find_effect_kind("load_cell_gain"), gains, 3);
  EXPECT_EQ(number(rig::with_offsets(*g, Eigen::VectorXd::Constant(1, -2.0)), "gain"), 0.5);
  EXPECT_EQ(number(rig::with_offsets(*g, Eigen::VectorXd::Constant(1, 3.0)), "gain"), 2.0);
  rig::RangeScales scales;
  scales.body_mass = 10.0;
  V bounded = V::map().set("mass", V::of(2.0)).set("uncertainty", V::map().set("mass", V::of(1.0)));
  const auto b = rig::take_uncertainty(*rig::find_effect_kind("rod_mass"), bounded, 3, scales);
  EXPECT_EQ(number(rig::with_offsets(*b, Eigen::VectorXd::Constant(1, 50.0)), "mass"), 10.0);
}

}  // namespace

// A fitted effect's uncertainty, as diagnose writes it into its effects
// files: a key that is a parameter itself gets its standard deviation; a
// key computed from the parameters gets it propagated to first order (a
// stiffness k = 1 / c: sigma_k = sigma_c / c^2 within the secant's 10 %
// over one sigma of 10 % of c); a key fed by two parameters the quadrature
// of both; a key that does not move (clamped at zero) gets none; and the
// block reads back through take_uncertainty with those deviations.
TEST(EffectUncertainty, FittedUncertaintyIsPropagatedFromTheFit) {
  const rig::EffectKind& lengths = *rig::find_effect_kind("rod_length_error");
  auto delta = [](const Eigen::VectorXd& p) { return V::map().set("delta", V::of(p)); };
  const Eigen::VectorXd theta = Eigen::Vector3d(0.003, -0.002, 0.0);
  const Eigen::VectorXd sd = Eigen::Vector3d(1e-4, 2e-4, 3e-4);
  const auto u = rig::fitted_uncertainty(lengths, delta, theta, sd);
  ASSERT_TRUE(u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(number(*u, "delta", i), sd(i), 1e-15) << i;
  V tree = delta(theta).set("uncertainty", *u);
  const auto back = rig::take_uncertainty(lengths, tree, 3);
  ASSERT_TRUE(back);
  ASSERT_EQ(back->items.size(), 3u);
  EXPECT_NEAR(back->items[1].sigma, 2e-4, 1e-15);

  const rig::EffectKind& rods = *rig::find_effect_kind("rod_compliance");
  auto stiffness = [](const Eigen::VectorXd& p) { return V::map().set("stiffness", V::of(1.0 / p(0))); };
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(1, 1e-6), sc = Eigen::VectorXd::Constant(1, 1e-7);
  const auto uk = rig::fitted_uncertainty(rods, stiffness, c, sc);
  ASSERT_TRUE(uk);
  EXPECT_NEAR(number(*uk, "stiffness"), 1e-7 / 1e-12, 0.1 * 1e-7 / 1e-12);

  const rig::EffectKind& friction = *rig::find_effect_kind("joint_friction");
  auto both = [](const Eigen::VectorXd& p) {
    return V::map().set("viscous", V::of(p(0) + p(1))).set("coulomb", V::of(std::max(p(1), 0.0) * 0.0));
  };
  const auto uf = rig::fitted_uncertainty(friction, both, Eigen::Vector2d(0.2, 0.1), Eigen::Vector2d(0.03, 0.04));
  ASSERT_TRUE(uf);
  EXPECT_NEAR(number(*uf, "viscous"), 0.05, 1e-12);
  EXPECT_FALSE((*uf)["coulomb"].defined());
  // Only vector keys: none at all.
  const rig::EffectKind& joints = *rig::find_effect_kind("joint_position_error");
  auto upper = [](const Eigen::VectorXd& p) { return V::map().set("upper", V::list({V::of(p), V::of(p), V::of(p)})); };
  EXPECT_FALSE(rig::fitted_uncertainty(joints, upper, Eigen::Vector3d(1e-3, 0, 0), Eigen::Vector3d(1e-4, 1e-4, 1e-4)));
}

// A frame's fitted compliances give one relative deviation of its
// stiffness: 1 / sqrt(sum (c_i / sigma_i)^2) over the compliances fitted
// above zero (here 2e-6 +- 1e-7 and 3e-6 +- 3e-7: 20 and 10, so 1/sqrt(500));
// it reads back as the frame's `{stiffness: s}`. A fit that does not fix
// the frame's size (s >= 1) or fitted nothing gives none.
TEST(EffectUncertainty, AFramesFittedStiffnessUncertainty) {
  const rig::EffectKind& frame = *rig::find_effect_kind("carrying_frame_flexibility");
  auto map = [](const Eigen::VectorXd&) { return V::map(); };  // a frame's block is not read for this
  const Eigen::VectorXd theta = (Eigen::VectorXd(5) << 2e-6, 3e-6, 0.0, 0.0, 0.0).finished();
  const Eigen::VectorXd sd = (Eigen::VectorXd(5) << 1e-7, 3e-7, 1e-7, 1e-7, 1e-7).finished();
  const auto u = rig::fitted_uncertainty(frame, map, theta, sd);
  ASSERT_TRUE(u);
  EXPECT_NEAR(number(*u, "stiffness"), 1.0 / std::sqrt(500.0), 1e-15);
  V tree = V::map().set("uncertainty", *u);
  const auto back = rig::take_uncertainty(frame, tree, 3);
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->frame_stiffness);
  EXPECT_NEAR(back->items[0].sigma, 100.0 / std::sqrt(500.0), 1e-12);
  // Every compliance at 0.4 of its deviation: s = 1 / sqrt(5 x 0.16) > 1, none; nothing fitted: none.
  EXPECT_FALSE(rig::fitted_uncertainty(frame, map, 0.4 * sd, sd));
  EXPECT_FALSE(rig::fitted_uncertainty(frame, map, Eigen::VectorXd::Zero(5), sd));
}
