// The chain's pieces (diagnose/effect_chain.hpp): a group of effects acts as
// its members applied one after another, and a candidate chained on
// accepted effects lays out, builds and writes all of them. The chain
// itself runs in tests/acceptance/test_uncertain_body.cpp ("two_effects").
#include <gtest/gtest.h>

#include "diagnose/effect_candidates.hpp"
#include "diagnose/effect_chain.hpp"
#include "rig/effects.hpp"
#include "support/effect_actions.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

const diagnose::EffectCandidate& named(const std::vector<diagnose::EffectCandidate>& all, const std::string& n) {
  for (const auto& c : all) {
    if (c.effect == n) return c;
  }
  throw std::invalid_argument("no candidate " + n);
}

Eigen::VectorXd probes(const diagnose::EffectCandidate& c, double factor) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(c.parameters.size()));
  for (Eigen::Index k = 0; k < x.size(); ++k)
    x(k) = factor * c.parameters[static_cast<size_t>(k)].probe * (1.0 + 0.3 * k);
  return x;
}

// Members that touch every hook: geometry (rod lengths), loads (drag) and
// the measurement chain (gains then offsets, whose order matters).
TEST(EffectGroup, ActsAsItsMembersOneAfterAnother) {
  const rig::RigModel m = test::noisy_trifilar();
  const auto lengths = std::make_shared<rig::RodLengthError>(std::vector<double>{0.003, -0.002, 0.0});
  const auto drag = std::make_shared<rig::AirDrag>(rig::AirDragParameters{1.2, 2.0, 5.0, std::nullopt});
  const auto gains =
      std::make_shared<rig::LoadCellGain>(std::vector<double>{1.01, 0.99, 1.02}, std::vector<double>{5.0, 0.0, -5.0});
  const auto offsets = std::make_shared<rig::EncoderOffset>(std::vector<double>{0.002, -0.001, 0.0},
                                                            std::vector<double>{0.0, 0.001, -0.002});
  const diagnose::EffectGroup g({lengths, drag, gains, offsets});
  EXPECT_EQ(std::string(g.name()), "rod_length_error+air_drag+load_cell_gain+encoder_offset");
  EXPECT_TRUE(g.dissipative());
  EXPECT_NO_THROW(g.validate(3));
  EXPECT_THROW(g.validate(4), std::invalid_argument);  // a member's own check
  EXPECT_THROW(diagnose::EffectGroup({}), std::invalid_argument);

  rig::RigAssembly one = test::built(g, m), each;
  each.geometry = m.geometry;
  each.body = m.body;
  for (const rig::Effect* e :
       std::initializer_list<const rig::Effect*>{lengths.get(), drag.get(), gains.get(), offsets.get()})
    e->build(each);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(one.geometry.rods[i].length, each.geometry.rods[i].length);
  EXPECT_NE(one.geometry.rods[0].length, m.geometry.rods[0].length);

  const rig::Kinematics k = test::moving(m.geometry);
  rig::Loads lg, ld;
  lg.reset(3);
  ld.reset(3);
  g.add_loads(k, lg);
  drag->add_loads(k, ld);
  EXPECT_EQ(lg.body_force, ld.body_force);
  EXPECT_GT(lg.body_force.norm(), 0.0);

  rig::SensorSample s;
  s.force = Eigen::VectorXd::Constant(3, 654.0);
  s.alpha = Eigen::VectorXd::Constant(3, 0.01);
  s.beta = Eigen::VectorXd::Constant(3, -0.02);
  rig::SensorSample sg = s, se = s;
  g.measure(sg);
  gains->measure(se);
  offsets->measure(se);
  EXPECT_EQ(sg.force, se.force);
  EXPECT_EQ(sg.alpha, se.alpha);
  EXPECT_NE(sg.force, s.force);
  // Undone in reverse order, the measurement comes back.
  g.unmeasure(sg);
  EXPECT_LE((sg.force - s.force).cwiseAbs().maxCoeff(), 1e-12 * 654.0);
  EXPECT_LE((sg.alpha - s.alpha).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((sg.beta - s.beta).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(ChainedCandidate, TheAcceptedParametersFirstThenTheNext) {
  const rig::RigSystem sys(test::noisy_trifilar());
  const auto all = diagnose::effect_candidates(diagnose::candidate_context(sys, 0.5));
  const auto& lengths = named(all, "rod_length_error");
  const auto& gains = named(all, "load_cell_gain");
  const Eigen::VectorXd a = probes(lengths, 3.0), b = probes(gains, 2.0);
  const std::vector<const diagnose::EffectCandidate*> accepted{&lengths};
  const diagnose::EffectCandidate c = diagnose::chained_candidate(accepted, &gains);
  EXPECT_EQ(c.effect, "load_cell_gain");
  EXPECT_EQ(c.advice, gains.advice);
  const size_t pa = lengths.parameters.size(), pb = gains.parameters.size();
  ASSERT_EQ(c.parameters.size(), pa + pb);
  EXPECT_EQ(c.parameters[0].name, "rod_length_error." + lengths.parameters[0].name);
  EXPECT_EQ(c.parameters[pa].name, gains.parameters[0].name);
  EXPECT_EQ(c.parameters[pa].probe, gains.parameters[0].probe);

  Eigen::VectorXd theta(static_cast<Eigen::Index>(pa + pb));
  theta << a, b;
  const auto made = c.make(theta);
  ASSERT_TRUE(made);
  const diagnose::EffectGroup both({lengths.make(a), gains.make(b)});
  test::expect_same_action(*made, both, test::noisy_trifilar(), 1e-15);
  EXPECT_EQ(c.rig_block(theta, {}), lengths.rig_block(a, {}) + gains.rig_block(b, {}));

  // A next effect at a value that amounts to none (a compliance of zero):
  // the accepted one alone, under its own name.
  const auto& compliance = named(all, "rod_compliance");
  const diagnose::EffectCandidate cz = diagnose::chained_candidate(accepted, &compliance);
  Eigen::VectorXd tz = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(pa + compliance.parameters.size()));
  tz.head(static_cast<Eigen::Index>(pa)) = a;
  ASSERT_TRUE(cz.make(tz));
  EXPECT_EQ(std::string(cz.make(tz)->name()), "rod_length_error");
  EXPECT_EQ(cz.rig_block(tz, {}), lengths.rig_block(a, {}));
  // Without a next one: the accepted effects alone, named after the last.
  const diagnose::EffectCandidate held = diagnose::chained_candidate(accepted, nullptr);
  EXPECT_EQ(held.effect, "rod_length_error");
  EXPECT_EQ(held.parameters.size(), pa);
  EXPECT_THROW(diagnose::chained_candidate({}, nullptr), std::invalid_argument);
}

}  // namespace

namespace {

// A fit beyond the effect's physical range (docs/rig.md) gives no block:
// the rig reader would refuse the file, so diagnose writes none (and says
// why in the candidate's note). Inside the range, the block reads back.
TEST(EffectCandidates, ABlockBeyondThePhysicalRangeIsRefused) {
  const rig::RigSystem sys(test::noisy_trifilar());  // rods of 1 m
  const auto all = diagnose::effect_candidates(diagnose::candidate_context(sys, 0.5));
  const auto& lengths = named(all, "rod_length_error");
  EXPECT_NO_THROW(lengths.rig_block(Eigen::Vector3d(0.19, 0.0, -0.19), {}));
  EXPECT_THROW(lengths.rig_block(Eigen::Vector3d(0.0, 0.3, 0.0), {}), rig::ParameterError);
  const auto& compliance = named(all, "rod_compliance");
  const double weight_per_rod = sys.suspended_weight() / 3;
  // A compliance that stretches the rods by 0.1 m under their load is read; 0.5 m is not a rod.
  EXPECT_NO_THROW(compliance.rig_block(Eigen::VectorXd::Constant(1, 0.1 / weight_per_rod), {}));
  EXPECT_THROW(compliance.rig_block(Eigen::VectorXd::Constant(1, 0.5 / weight_per_rod), {}), rig::ParameterError);
}

}  // namespace
