// compare's refit of the model's own parameters (diagnose/baseline_fit.hpp,
// ModelComparisonOptions::fit_model): a user's CoG is never exact, and its
// error must not show as the model's. Records of the trifilar of the
// diagnose tests (6 histories of 15 s, 1 N and 2e-5 rad of noise).
#include <gtest/gtest.h>

#include <cmath>

#include "diagnose/model_comparison.hpp"
#include "rig/effects.hpp"
#include "support/diagnosis_cases.hpp"
#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

using test::named;

diagnose::ModelComparison compare(const rig::RigModel& model, const std::vector<rig::Record>& data, bool fit) {
  diagnose::ModelComparisonOptions o;
  o.fit_model = fit;
  o.identify = false;
  return diagnose::compare_model(diagnose::ResponseModel(model), test::record_pointers(data), {}, o);
}

// The rig file's CoG 5 mm too high and 2 mm off in x (within the stated
// 3/3/7 mm): the refit finds the offsets back within 3 of their standard
// deviations (plus 0.1 mm for the prediction's period error, which a CoG
// height absorbs: docs/compare.md, Limits), the
// comparison is made with the refitted model and its force NRMSE falls to
// the noise's (the body error, not the model, made the rest); the
// rig file's figures are kept beside it, equal to --hold-body's.
TEST(ModelParameterFit, CompareFindsTheBodysOffsetAndComparesTheRefittedModel) {
  const rig::RigModel truth = test::noisy_trifilar();
  const auto data = test::measure_histories(truth, 41);
  rig::RigModel user = truth;
  user.body.cog += rig::Vec3(0.002, 0.0, 0.005);
  const diagnose::ModelComparison held = compare(user, data, false);
  const diagnose::ModelComparison c = compare(user, data, true);
  EXPECT_FALSE(held.model_fit);
  ASSERT_TRUE(c.model_fit);
  const diagnose::ModelParameterFit& f = *c.model_fit;
  EXPECT_TRUE(f.credible);
  EXPECT_TRUE(f.off.empty());
  const auto& z = named(f.parameters, "cog_z");
  const auto& x = named(f.parameters, "cog_x");
  EXPECT_NEAR(z.value, -0.005, 3 * z.std + 1e-4);
  EXPECT_NEAR(x.value, -0.002, 3 * x.std + 1e-4);
  EXPECT_NEAR(f.model.body.cog.z(), truth.body.cog.z(), 3 * z.std + 1e-4);
  EXPECT_LT(f.noise_ratio, f.noise_ratio_as_stated);
  ASSERT_TRUE(c.as_stated);
  EXPECT_EQ(c.as_stated->force, held.force_nrmse);
  EXPECT_EQ(c.as_stated->overall, held.overall_nrmse);
  // The noise alone gives a force NRMSE of about 0.006 here (docs/compare.md).
  EXPECT_LT(c.force_nrmse, 0.5 * held.force_nrmse);
  EXPECT_LT(c.force_nrmse, 0.01);
}

// The same CoG error against a rig file that claims 1 mm in height: the
// data move it beyond 3 of those, and it is reported off.
TEST(ModelParameterFit, AnOffsetBeyondTheStatedUncertaintyIsOff) {
  const rig::RigModel truth = test::noisy_trifilar();
  const auto data = test::measure_histories(truth, 43);
  rig::RigModel user = truth;
  user.body.cog.z() += 0.005;
  user.body_uncertainty.cog = rig::Vec3(0.003, 0.003, 0.001);
  const diagnose::ModelComparison c = compare(user, data, true);
  ASSERT_TRUE(c.model_fit);
  ASSERT_TRUE(c.model_fit->credible);
  ASSERT_EQ(c.model_fit->off.size(), 1u);
  EXPECT_EQ(c.model_fit->off.front().name, "cog_z");
  EXPECT_LT(c.model_fit->off.front().value, -0.003);
}

// A model that misses an effect by far (rods 3 mm long and short): the
// refit cannot reach the noise, its offsets would absorb the effect, so
// the comparison stays the rig file's model's and says so.
TEST(ModelParameterFit, AMissingEffectKeepsTheRigFilesModel) {
  rig::RigModel truth = test::noisy_trifilar();
  truth.effects.push_back(std::make_shared<rig::RodLengthError>(std::vector<double>{0.003, -0.003, 0.0}));
  const auto data = test::measure_histories(truth, 47);
  const rig::RigModel user = test::noisy_trifilar();
  const diagnose::ModelComparison held = compare(user, data, false);
  const diagnose::ModelComparison c = compare(user, data, true);
  ASSERT_TRUE(c.model_fit);
  EXPECT_FALSE(c.model_fit->credible);
  EXPECT_GT(c.model_fit->noise_ratio, 1.0 + diagnose::DiagnosisOptions{}.noise_excess);
  EXPECT_FALSE(c.as_stated);
  EXPECT_EQ(c.force_nrmse, held.force_nrmse);
  EXPECT_EQ(c.model_fit->model.body.cog, user.body.cog);
}

// Nothing stated uncertain: nothing to refit, the comparison as given.
TEST(ModelParameterFit, NothingUncertainNothingRefitted) {
  const rig::RigModel truth = test::noisy_trifilar();
  const auto data = test::measure_histories(truth, 53);
  rig::RigModel user = truth;
  user.body_uncertainty.cog = rig::Vec3::Zero();
  user.body_uncertainty.inertia = std::array<double, 6>{};
  const diagnose::ModelComparison c = compare(user, data, true);
  EXPECT_FALSE(c.model_fit);
}

}  // namespace
