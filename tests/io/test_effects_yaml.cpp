// Effects files round trip through the one writer (rig::effect_yaml,
// io::effects_file_text) and the rig reader, for every kind of the
// catalogue: the effect read back is the one diagnose fitted, and the text
// written again from what was read is the same text.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/effects_file.hpp"
#include "io/rig_reader.hpp"
#include "io/yaml_parameters.hpp"
#include "rig/effect_kinds.hpp"
#include "support/effect_actions.hpp"
#include "support/rig_cases.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

// Each value as the writer's 6 significant digits read back.
Eigen::VectorXd rounded(Eigen::VectorXd x) {
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    std::ostringstream s;
    s << std::setprecision(6) << x(k);
    x(k) = std::stod(s.str());
  }
  return x;
}

TEST(EffectsYaml, EveryKindRoundTrips) {
  const test::TempDir dir("effects_yaml");
  for (const auto& kind : rig::effect_kinds()) {
    const rig::RigModel start = test::multifilar_rig();
    const rig::EffectFitting f = kind.fit(test::fit_context(start));
    const Eigen::VectorXd x = rounded(test::sample_values(f));
    const std::string block = rig::effect_yaml(kind.name, f.write(x));
    const std::string text = io::effects_file_text({"round trip"}, block);
    test::write_text(dir.path() / "e.yaml", text);
    rig::RigModel m = start;
    io::add_effects(m, dir.path() / "e.yaml");
    ASSERT_NE(m.effect(kind.name), nullptr) << text;
    test::expect_same_action(*f.make(x), *m.effect(kind.name), start, 1e-5);
    // Written again from what was read: the same text.
    const YAML::Node root = YAML::Load(text);
    EXPECT_EQ(rig::effect_yaml(kind.name, io::parameter_tree(root["effects"][kind.name])), block);
  }
}

TEST(EffectsYaml, FileText) {
  EXPECT_EQ(io::effects_file_text({"one", "two."}, "rod_mass: {mass: 2}\n"),
            "# one\n# two.\neffects:\n  rod_mass: {mass: 2}\n");
}

}  // namespace
}  // namespace rigflex
