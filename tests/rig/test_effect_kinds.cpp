// The effect catalogue's table (rig/effect_kinds.hpp): every kind complete
// (parameters with units and ranges, a parser, a fit), parse(write(x)) the
// effect diagnose makes from x for every kind, the one YAML writer's text,
// and the docs' effect tables equal to what the table generates.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <string>

#include "rig/effect_kinds.hpp"
#include "rig/effect_ranges.hpp"
#include "rig/rig_system.hpp"
#include "support/effect_actions.hpp"
#include "support/rig_cases.hpp"

using namespace rigflex;

namespace {

bool numeric(rig::ParameterShape s) {
  return s != rig::ParameterShape::text && s != rig::ParameterShape::map;
}

std::string shape_text(rig::ParameterShape s) {
  switch (s) {
    case rig::ParameterShape::per_rod: return "per rod (or one for all)";
    case rig::ParameterShape::per_rod_vec3: return "[x, y, z] per rod";
    case rig::ParameterShape::vec3: return "[x, y, z]";
    case rig::ParameterShape::pair: return "[x, y]";
    case rig::ParameterShape::integer: return "integer";
    default: return "";
  }
}

std::string parameter_text(const rig::ParameterSpec& p) {
  std::string s = "`" + p.key + "`";
  for (const std::string& part : {p.unit == "1" ? std::string() : p.unit, rig::range_text(p), shape_text(p.shape)}) {
    if (!part.empty()) s += " " + part;
  }
  if (!p.default_value.empty()) s += " (default " + p.default_value + ")";
  return s + ": " + p.doc;
}

// docs/rig.md's effect table, as the catalogue states it.
std::string rig_table() {
  std::string s = "| effect | hook | parameters (unit, physical range, shape) | enters the equations | signature |\n"
                  "|---|---|---|---|---|\n";
  for (const auto& k : rig::effect_kinds()) {
    std::string params;
    for (const auto& p : k.parameters) params += (params.empty() ? "" : "; ") + parameter_text(p);
    s += "| " + k.name + " | " + rig::hook_name(k.hook) + " | " + params + " | " + k.equations + " | " + k.signature +
         " |\n";
  }
  return s;
}

// docs/compare.md's table of diagnose's parameterizations.
std::string fit_table() {
  std::string s = "| effect | fitted through |\n|---|---|\n";
  for (const auto& k : rig::effect_kinds()) s += "| " + k.name + " | " + k.fitted_through + " |\n";
  return s;
}

// The table of `doc` whose first line is `header`: its lines up to the first that is no table row.
std::string table_in(const std::string& doc, const std::string& header) {
  std::ifstream in(std::string(RIGFLEX_SOURCE_DIR) + "/" + doc);
  std::string out, line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == header) inside = true;
    if (inside && line.rfind("|", 0) != 0) break;
    if (inside) out += line + "\n";
  }
  return out;
}

}  // namespace

TEST(EffectKinds, EveryKindIsComplete) {
  ASSERT_EQ(rig::effect_kinds().size(), rig::effect_names().size());
  std::set<std::string> names;
  for (size_t i = 0; i < rig::effect_kinds().size(); ++i) {
    const rig::EffectKind& k = rig::effect_kinds()[i];
    EXPECT_EQ(k.name, rig::effect_names()[i]);
    EXPECT_EQ(rig::find_effect_kind(k.name), &k);
    EXPECT_TRUE(names.insert(k.name).second) << k.name;
    EXPECT_FALSE(k.equations.empty() || k.signature.empty() || k.fitted_through.empty()) << k.name;
    EXPECT_TRUE(k.parse && k.fit) << k.name;
    ASSERT_FALSE(k.parameters.empty()) << k.name;
    for (const auto& p : k.parameters) {
      EXPECT_FALSE(p.key.empty() || p.doc.empty()) << k.name;
      if (!numeric(p.shape)) continue;
      EXPECT_FALSE(p.unit.empty()) << k.name << "." << p.key;
      EXPECT_LT(p.low, p.high) << k.name << "." << p.key;
    }
  }
  EXPECT_EQ(rig::find_effect_kind("rod_complience"), nullptr);
}

// Every fit's parameters carry units and plausible ranges around zero or above it.
TEST(EffectKinds, FitParametersHaveUnitsAndRanges) {
  const rig::RigModel m = test::multifilar_rig();
  for (const auto& k : rig::effect_kinds()) {
    const rig::EffectFitting f = k.fit(test::fit_context(m));
    ASSERT_FALSE(f.parameters.empty()) << k.name;
    EXPECT_FALSE(f.advice.empty()) << k.name;
    EXPECT_FALSE(f.evidence.empty()) << k.name;
    for (const auto& p : f.parameters) {
      EXPECT_FALSE(p.unit.empty()) << k.name << "." << p.name;
      EXPECT_GT(p.probe, 0) << k.name << "." << p.name;
      EXPECT_LT(p.low, p.high) << k.name << "." << p.name;
      if (p.non_negative) {
        EXPECT_GE(p.low, 0) << k.name << "." << p.name;
      }
    }
  }
}

// parse(write(x)) is the effect the fit makes of x, for every kind.
TEST(EffectKinds, ParseOfWriteIsTheFittedEffect) {
  const rig::RigModel m = test::multifilar_rig();
  for (const auto& k : rig::effect_kinds()) {
    const rig::EffectFitting f = k.fit(test::fit_context(m));
    const Eigen::VectorXd x = test::sample_values(f);
    const auto made = f.make(x);
    ASSERT_TRUE(made) << k.name;
    const auto parsed = k.parse(f.write(x), rig::parse_context(m, k.name));
    ASSERT_TRUE(parsed) << k.name;
    EXPECT_NO_THROW(parsed->validate(m.geometry.rod_count())) << k.name;
    test::expect_same_action(*made, *parsed, m, 1e-12);
  }
}

// With the rig file's nominal rods the fitted compliance adds to theirs in
// series: zero is the model as it is, and the file diagnose writes gives
// the total; parse(write(x)) still the fitted effect.
TEST(EffectKinds, RodComplianceAddsToTheNominalRods) {
  rig::RigModel m = test::multifilar_rig();
  m.rods.stiffness = {2.0e6, 4.0e6, 1.0e6};
  const rig::EffectKind* k = rig::find_effect_kind("rod_compliance");
  ASSERT_TRUE(k);
  const rig::EffectFitting f = k->fit(test::fit_context(m));
  EXPECT_EQ(f.make(Eigen::VectorXd::Zero(1)), nullptr);
  const double added = 5e-7;  // m/N
  const auto made = f.make(Eigen::VectorXd::Constant(1, added));
  ASSERT_TRUE(made);
  rig::RigModel with = m;
  with.effects.push_back(made);
  const Eigen::VectorXd got = rig::RigSystem(with).rod_stiffness();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got(i), 1.0 / (1.0 / m.rods.stiffness[i] + added), 1e-9 * got(i)) << i;
  const auto parsed = k->parse(f.write(Eigen::VectorXd::Constant(1, added)), rig::parse_context(m, k->name));
  ASSERT_TRUE(parsed);
  test::expect_same_action(*made, *parsed, m, 1e-12);
}

// The writer's text, as diagnose has always written it: one line when every
// parameter is a number or a flat list, else a block.
TEST(EffectKinds, YamlText) {
  using V = rig::ParameterValue;
  EXPECT_EQ(rig::effect_yaml("rod_mass", V::map().set("mass", V::of(2.5))), "rod_mass: {mass: 2.5}\n");
  EXPECT_EQ(rig::effect_yaml("encoder_offset", V::map().set("alpha", V::of(std::vector<double>{1e-3, -2.0 / 3}))),
            "encoder_offset: {alpha: [0.001, -0.666667]}\n");
  const V upper = V::list({V::of(std::vector<double>{0, 0, 1}), V::of(std::vector<double>{1, 2, 3})});
  EXPECT_EQ(rig::effect_yaml("joint_position_error", V::map().set("upper", upper)),
            "joint_position_error:\n  upper: [[0, 0, 1], [1, 2, 3]]\n");
  const V jc = V::map().set("translation", V::of(std::vector<double>{1, 2, 3})).set("rocking", V::of(0.5));
  EXPECT_EQ(rig::effect_yaml("carrying_frame_flexibility", V::map().set("joint_compliance", jc), 2),
            "  carrying_frame_flexibility:\n    joint_compliance:\n      translation: [1, 2, 3]\n      rocking: 0.5\n");
}

// A parameter the catalogue cannot use names its line and key.
TEST(EffectKinds, ParseErrorsNameLineAndKey) {
  const rig::RigModel m = test::multifilar_rig();
  const rig::EffectKind& k = *rig::find_effect_kind("rod_mass");
  rig::ParameterValue e = rig::ParameterValue::map();
  rig::ParameterValue wrong = rig::ParameterValue::list({rig::ParameterValue::of(1.0)});
  wrong.line = 7;
  e.set("mass", wrong);
  try {
    k.parse(e, rig::parse_context(m, k.name));
    FAIL() << "a list of one mass for three rods was taken";
  } catch (const rig::ParameterError& x) {
    EXPECT_EQ(x.line(), 7);
    EXPECT_EQ(x.key(), "mass");
    EXPECT_EQ(x.reason(), "expected a list of 3 numbers");
  }
}

// The docs' effect tables are the catalogue's: regenerate them from this
// test's output when the table changes.
TEST(EffectKinds, DocsTablesFollowTheTable) {
  const std::string rig = rig_table(), fit = fit_table();
  EXPECT_EQ(table_in("docs/rig.md", rig.substr(0, rig.find('\n'))), rig) << "docs/rig.md should hold:\n" << rig;
  EXPECT_EQ(table_in("docs/compare.md", fit.substr(0, fit.find('\n'))), fit) << "docs/compare.md should hold:\n"
                                                                               << fit;
}
