// An integrator failure as the command line reports it (io/integration_error):
// the rig and effects files, the effects in the model, the time, the
// integrator's reason and the cures that fit the integrator that failed.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "io/integration_error.hpp"
#include "rig/effects.hpp"

namespace rigflex::io {
namespace {

bool has(const std::string& text, const std::string& words) { return text.find(words) != std::string::npos; }

TEST(IntegrationError, NamesTheFilesTheEffectsTheTimeAndTheCures) {
  rig::RigModel model;
  model.effects.push_back(std::make_shared<rig::RodCompliance>(std::vector<double>{1e7, 1e7, 1e7}));
  const rig::IntegrationFailure failure("generalized-alpha", 0.002, "Newton iterations did not converge");
  const std::string text =
      integration_error(failure, model, {"rig.yaml", "effects/fixed_frame_flexibility.yaml"}).what();
  EXPECT_TRUE(has(text, "rig.yaml, effects/fixed_frame_flexibility.yaml: ")) << text;
  EXPECT_TRUE(has(text, "t = 0.002")) << text;
  EXPECT_TRUE(has(text, "Newton iterations did not converge")) << text;
  EXPECT_TRUE(has(text, "effects in the model: rod_compliance")) << text;
  EXPECT_TRUE(has(text, "method: bdf")) << text;

  model.simulation.method = rig::IntegrationMethod::bdf;
  model.effects.clear();
  const std::string bdf = integration_error(rig::IntegrationFailure("CVODE BDF", 1.5, "CVode failed (CV_CONV_FAILURE)"),
                                            model, {"rig.yaml"})
                              .what();
  EXPECT_TRUE(has(bdf, "effects in the model: none")) << bdf;
  EXPECT_TRUE(has(bdf, "relative_tolerance")) << bdf;
  EXPECT_FALSE(has(bdf, "method: bdf}")) << bdf;
}

}  // namespace
}  // namespace rigflex::io
