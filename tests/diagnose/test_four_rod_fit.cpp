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

#include <memory>
#include <vector>

#include "diagnose/diagnosis.hpp"
#include "rig/effects.hpp"
#include "support/diagnosis_cases.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

// 250 kg on four vertical 1.2 m rods of 2e7 N/m at the corners of a
// 1.1 x 0.84 m rectangle, the spec's sensor noise; the user's model with
// the CoG off by 2/2/6 mm (within the stated 3/3/7) and the inertia within
// 5 % (with parallel rods the rigid identification cannot observe roll and
// pitch inertia).
rig::RigModel four_rod_rig() {
  rig::RigModel m = test::multifilar_rig(4, 0.6, 1.2, 250.0, 0.7, 0.25);
  const double corner[4][2] = {{0.55, 0.42}, {-0.55, 0.42}, {-0.55, -0.42}, {0.55, -0.42}};
  for (int i = 0; i < 4; ++i) {
    rig::RodGeometry& rod = m.geometry.rods[i];
    rod.lower = rig::Vec3(corner[i][0], corner[i][1], 0.0);
    rod.upper = rod.lower + rig::Vec3(0, 0, 1.2);
    rod.encoder_axis = rig::Vec3(1, 0, 0);
  }
  m.body.cog = rig::Vec3(0.03, 0.02, -0.25);
  m.body.inertia << 22, 0.4, -0.8, 0.4, 30, 0.3, -0.8, 0.3, 40;
  m.rods.stiffness.assign(4, 2e7);
  m.sensors.sample_rate_hz = 500;
  m.sensors.force_noise_n = 1.0;
  m.sensors.angle_noise_rad = 2e-5;
  return m;
}

TEST(FourRodRig, RodLengthErrorFitMovesTheCogHeightWhereTheRecordsPutIt) {
  rig::RigModel truth = four_rod_rig();
  truth.effects.push_back(std::make_shared<rig::RodLengthError>(std::vector<double>{2e-5, 0.0, 0.0, 0.0}));
  rig::RigModel model = four_rod_rig();
  model.body.cog += rig::Vec3(0.002, -0.002, 0.006);
  model.body.inertia = Eigen::Vector3d(23, 29, 41).asDiagonal();
  const std::vector<rig::Record> records = test::measure_histories(truth, 22);
  diagnose::DiagnosisOptions o;
  o.effects = {"rod_length_error"};
  const diagnose::Diagnosis d = diagnose::diagnose(model, test::record_pointers(records), {}, o);
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

}  // namespace
