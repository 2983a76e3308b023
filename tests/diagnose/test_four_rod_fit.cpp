// A rod length error on a four-rod rig. Four rods on a rigid carrying frame
// are statically indeterminate: the crossed combination of the four lengths
// shifts the rod forces at rest (here some 100 N against 1 N of noise),
// while the other three combinations (all rods longer, two tilts) barely
// show. Two ways the fit went wrong here, each asserted against:
//  - the normal equations span many orders of magnitude; a Gauss-Newton
//    step whose truncated inverse is not equilibrated (diagnose/
//    joint_fit.cpp) cut the body's CoG height as negligible beside the
//    crossed combination and left it 6 mm off, the fit at 5.9 x the noise;
//  - a probe of 1 mm per rod length is a ~5 kN self-stress on these rods
//    (rig/effect_kind_entries.hpp, FitScales::axial_probe): its
//    finite-difference Jacobian was a secant far outside the linear range,
//    and the fit stopped at 1.37 x the noise with the tilts 0.04 and
//    0.07 mm off.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "diagnose/diagnosis.hpp"
#include "diagnose/effect_candidates.hpp"
#include "rig/effects.hpp"
#include "rig/rig_system.hpp"
#include "support/diagnosis_cases.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

// The rig with `hidden` measured (six records of 15 s, `seed`), diagnosed
// from the user's model - the CoG off by 2/2/6 mm (within the stated
// 3/3/7), the inertia within 5 % (with parallel rods the rigid
// identification cannot observe roll and pitch inertia) - with `effect`
// the only candidate.
diagnose::Diagnosis diagnose_hidden(std::shared_ptr<const rig::Effect> hidden, const std::string& effect,
                                    std::uint64_t seed) {
  rig::RigModel truth = test::noisy_quadrifilar();
  truth.effects.push_back(std::move(hidden));
  rig::RigModel model = test::noisy_quadrifilar();
  model.body.cog += rig::Vec3(0.002, -0.002, 0.006);
  model.body.inertia = Eigen::Vector3d(23, 29, 41).asDiagonal();
  const std::vector<rig::Record> records = test::measure_histories(truth, seed);
  diagnose::DiagnosisOptions o;
  o.effects = {effect};
  return diagnose::diagnose(model, test::record_pointers(records), {}, o);
}

TEST(FourRodRig, RodLengthErrorFitMovesTheCogHeightWhereTheRecordsPutIt) {
  const diagnose::Diagnosis d = diagnose_hidden(
      std::make_shared<rig::RodLengthError>(std::vector<double>{2e-5, 0.0, 0.0, 0.0}), "rod_length_error", 22);
  ASSERT_EQ(d.missing_effect.value_or("none"), "rod_length_error") << d.summary;
  const diagnose::EffectFit& fit = d.ranking.front();
  // The model with the true body and lengths sits at the noise (1.0 x, its
  // residual's expectation; 0.98 measured with the fitted ones); 1.1 x
  // leaves room for the fit's own noise (the nine body properties and 24
  // swing states fitted on 6 x 15 s) and fails the fits that stopped at
  // 1.37 and 5.9 x.
  EXPECT_LT(fit.residual / d.samples, 1.1) << d.summary;
  // d.body is empty unless the fit reaches the noise: `named` throws then.
  // Each CoG coordinate within 0.5 mm (1/4 of the smallest offset; the
  // records determine them to 0.002-0.07 mm) of the truth.
  EXPECT_NEAR(test::named(d.body, "cog_x").value, -0.002, 5e-4) << d.summary;
  EXPECT_NEAR(test::named(d.body, "cog_y").value, 0.002, 5e-4) << d.summary;
  EXPECT_NEAR(test::named(d.body, "cog_z").value, -0.006, 5e-4) << d.summary;
  ASSERT_EQ(fit.parameters.size(), 4u);
  const auto combination = [&](double s1, double s2, double s3, double s4) {
    return (s1 * fit.parameters[0].value + s2 * fit.parameters[1].value + s3 * fit.parameters[2].value +
            s4 * fit.parameters[3].value) /
           4.0;
  };
  // The crossed combination is what the forces show: 1/4 of 0.02 mm, to 10 %.
  EXPECT_NEAR(combination(1, -1, 1, -1), 5e-6, 5e-7);
  // The two tilts (rods at +y against -y, at +x against -x; each 1/4 of
  // 0.02 mm) show only through the body's attitude and the rods' angles:
  // within the hidden error's own size (0.02 mm), their standard deviations
  // being about 0.0015 mm.
  const double tilt_x = combination(1, 1, -1, -1), tilt_y = combination(1, -1, -1, 1);
  EXPECT_NEAR(tilt_x, 5e-6, 2e-5);
  EXPECT_NEAR(tilt_y, 5e-6, 2e-5);
  RecordProperty("residual_to_noise", std::to_string(fit.residual / d.samples));
  RecordProperty("tilts_um", std::to_string(1e6 * tilt_x) + " " + std::to_string(1e6 * tilt_y));
}

// Errors of the rig's four upper joints less their mean and their mean
// turn about the vertical through the joints' centroid (0, 0, 1.2).
std::vector<rig::Vec3> without_mean_and_turn(std::vector<rig::Vec3> e) {
  rig::Vec3 mean = rig::Vec3::Zero();
  for (const rig::Vec3& x : e) mean += x / 4.0;
  const rig::RigModel m = test::noisy_quadrifilar();
  double moment = 0, polar = 0;
  for (int i = 0; i < 4; ++i) {
    const rig::Vec3 r = m.geometry.rods[i].upper - rig::Vec3(0, 0, 1.2);
    e[i] -= mean;
    moment += r.x() * e[i].y() - r.y() * e[i].x();
    polar += r.x() * r.x() + r.y() * r.y();
  }
  for (int i = 0; i < 4; ++i) {
    const rig::Vec3 r = m.geometry.rods[i].upper - rig::Vec3(0, 0, 1.2);
    e[i] -= moment / polar * rig::Vec3(-r.y(), r.x(), 0.0);
  }
  return e;
}

// Upper joints 3 mm off sideways on a quadrifilar. Turning every upper joint
// about the vertical turns the whole suspended rig, which the records
// barely see: fitted, the turn drifted to 1.3 degrees, the joints' heights
// 50-90 mm off and the fit ended at 9.75 x the noise. Without it the fit
// reaches the noise and gives each joint's error less the mean and the turn
// that it cannot see (rig/effect_kinds_structure.cpp).
TEST(FourRodRig, JointPositionErrorFitReachesTheNoiseWithoutTheUnseenTurn) {
  const std::vector<rig::Vec3> hidden = {rig::Vec3(0.003, 0, 0), rig::Vec3(0, -0.003, 0), rig::Vec3(0.002, 0.002, 0),
                                         rig::Vec3::Zero()};
  const diagnose::Diagnosis d =
      diagnose_hidden(std::make_shared<rig::JointPositionError>(hidden, std::vector<rig::Vec3>(4, rig::Vec3::Zero())),
                      "joint_position_error", 23);
  ASSERT_EQ(d.missing_effect.value_or("none"), "joint_position_error") << d.summary;
  const diagnose::EffectFit& fit = d.ranking.front();
  // As the rod-length case above: the noise is 1.0 x.
  EXPECT_LT(fit.residual / d.samples, 1.1) << d.summary;
  EXPECT_NEAR(test::named(d.body, "cog_z").value, -0.006, 5e-4) << d.summary;
  // What the records can tell: the hidden errors less their mean and their
  // mean turn about the vertical through the joints' centroid (0.05 mm at
  // the joints here).
  std::vector<rig::Vec3> fitted;
  rig::Vec3 sum = rig::Vec3::Zero();
  ASSERT_EQ(fit.parameters.size(), 9u);
  for (int i = 0; i < 3; ++i) {
    fitted.push_back(
        rig::Vec3(fit.parameters[3 * i].value, fit.parameters[3 * i + 1].value, fit.parameters[3 * i + 2].value));
    sum += fitted.back();
  }
  fitted.push_back(-sum);
  const std::vector<rig::Vec3> seen = without_mean_and_turn(hidden), found = without_mean_and_turn(fitted);
  // Sideways within 0.1 mm (1/30 of the hidden 3 mm) of what the records
  // can tell; a joint's height trades against the CoG's horizontal place
  // (a tilt of the upper joints' plane) and is not asserted.
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(found[i].x(), seen[i].x(), 1e-4) << "joint " << i + 1;
    EXPECT_NEAR(found[i].y(), seen[i].y(), 1e-4) << "joint " << i + 1;
  }
  RecordProperty("residual_to_noise", std::to_string(fit.residual / d.samples));
}

// The candidates on four rods, without a fit (cheap enough for the
// sanitizer pass): the lengths along the rods probed by a quarter of the
// rods' static stretch, sideways by 1 mm; a turn of the upper joints about
// the vertical builds no joint error, an error without turn builds as
// given (each read back from the assembled geometry).
TEST(FourRodCandidates, LengthsProbedInTheLinearRangeAndJointErrorsWithoutTheTurn) {
  const rig::RigModel m = test::noisy_quadrifilar();
  const rig::RigSystem sys(m);
  const double quarter_stretch = 0.25 * sys.suspended_weight() / 4.0 / 2e7;  // 7.7 micrometres
  const auto candidates = diagnose::effect_candidates(diagnose::candidate_context(sys, 0.5));
  const auto find = [&](const std::string& name) {
    for (const auto& c : candidates) {
      if (c.effect == name) return c;
    }
    throw std::logic_error("no candidate " + name);
  };
  for (const auto& p : find("rod_length_error").parameters) EXPECT_DOUBLE_EQ(p.probe, quarter_stretch) << p.name;
  const diagnose::EffectCandidate jpe = find("joint_position_error");
  ASSERT_EQ(jpe.parameters.size(), 9u);
  for (size_t k = 0; k < 9; ++k) {
    EXPECT_DOUBLE_EQ(jpe.parameters[k].probe, k % 3 == 2 ? quarter_stretch : 1e-3) << jpe.parameters[k].name;
  }
  const auto built = [&](const std::vector<rig::Vec3>& e) {
    Eigen::VectorXd theta(9);
    for (int i = 0; i < 3; ++i) theta.segment<3>(3 * i) = e[i];
    rig::RigModel with = m;
    with.effects.push_back(jpe.make(theta));
    const rig::RigSystem s(with);
    std::vector<rig::Vec3> moved;
    for (int i = 0; i < 4; ++i) moved.push_back(s.assembly().geometry.rods[i].upper - m.geometry.rods[i].upper);
    return moved;
  };
  std::vector<rig::Vec3> turn;
  for (const auto& rod : m.geometry.rods) turn.push_back(1e-3 * rig::Vec3(-rod.upper.y(), rod.upper.x(), 0.0));
  for (const rig::Vec3& e : built(turn)) EXPECT_LT(e.norm(), 1e-15);
  const std::vector<rig::Vec3> plain = without_mean_and_turn(
      {rig::Vec3(0.003, 0, 0.001), rig::Vec3(0, -0.003, 0), rig::Vec3(0.002, 0.002, -0.002), rig::Vec3::Zero()});
  const std::vector<rig::Vec3> back = built(plain);
  for (int i = 0; i < 4; ++i) EXPECT_LT((back[i] - plain[i]).norm(), 1e-15) << "joint " << i + 1;
}

}  // namespace
