// The rig reader: a valid rig.yaml builds the model; each kind of bad input of
// issue 4 is refused with an InputError naming the file, the line and the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>

#include "fe/assembly_size.hpp"
#include "io/input_error.hpp"
#include "io/rig_reader.hpp"
#include "rig/effect.hpp"
#include "rig/effects.hpp"
#include "rig/rig_spec.hpp"
#include "rig/rig_system.hpp"
#include "support/temp_files.hpp"
#include "support/text_edits.hpp"

namespace rigflex {
namespace {

using test::replace_first;
using test::line_of;

// Three vertical rods of 1 m at 0.4 m around P (|A - P - B| = L exactly), a
// 100 kg body near the uniform disk of multifilar_rig() in
// tests/support/rig_cases.hpp (Jzz a little below Jxx + Jyy, so that the products
// of inertia keep the principal moments a triangle).
const char* kValidRig = R"(name: three-rod
geometry:
  gravity: 9.81
  reference_point: [0, 0, 0]
  rods:
    - upper: [0.4, 0.0, 1.0]
      lower: [0.4, 0.0, 0.0]
      length: 1.0
      encoder_axis: [1, 0, 0]
    - upper: [-0.2, 0.3464, 1.0]
      lower: [-0.2, 0.3464, 0.0]
      length: 1.0
      encoder_axis: [-0.5, 0.8660254037844386, 0]
    - upper: [-0.2, -0.3464, 1.0]
      lower: [-0.2, -0.3464, 0.0]
      length: 1.0
      encoder_axis: [0, 1, 0]
body:
  mass: 100.0
  cog: [0, 0, -0.1]
  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]
sensors:
  sample_rate: 250
  load_cell: {noise: 1.0}
  encoder: {bits: 17}
effects:
  encoder_offset: {alpha: [0.001, 0.002, 0.003], beta: 0.0}
  load_cell_gain: {gain: [1.0, 1.01, 0.99]}
  air_drag: {cd_area: 0.5, enabled: false}
)";

// The rig that `text`, written to a file, states.
rig::RigModel rig_of(const std::string& text) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", text);
  return io::read_rig(dir.path() / "rig.yaml");
}

// Reads `text` from a real file (the error must name it) and returns the
// error; fails the test if there is none.
io::InputError rig_error_of(const std::string& text) {
  const test::TempDir dir("rigflex-rig-reader");
  const auto file = dir.path() / "bad-rig.yaml";
  test::write_text(file, text);
  try {
    io::read_rig(file);
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    // what() carries all three, for the command line that prints it.
    EXPECT_NE(std::string(e.what()).find(file.string() + ":" + std::to_string(e.line()) + ": key '" + e.key() + "'"),
              std::string::npos)
        << e.what();
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return io::InputError("", 0, "", "");
}

// The error names `key` at the line holding `at`, and its message says `why`.
void expect_error(const std::string& text, const std::string& at, const std::string& key, const std::string& why) {
  const io::InputError e = rig_error_of(text);
  EXPECT_EQ(e.line(), line_of(text, at)) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_NE(e.reason().find(why), std::string::npos) << e.what();
}

TEST(RigReader, ReadsAValidRig) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", kValidRig);
  const rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  EXPECT_EQ(m.name, "three-rod");
  EXPECT_EQ(m.geometry.gravity, 9.81);
  ASSERT_EQ(m.geometry.rod_count(), 3);
  EXPECT_EQ(m.geometry.rods[1].upper, rig::Vec3(-0.2, 0.3464, 1.0));
  EXPECT_EQ(m.geometry.rods[1].lower, rig::Vec3(-0.2, 0.3464, 0.0));
  EXPECT_EQ(m.geometry.rods[2].encoder_axis, rig::Vec3(0, 1, 0));
  EXPECT_EQ(m.body.mass, 100.0);
  EXPECT_EQ(m.body.cog, rig::Vec3(0, 0, -0.1));
  // [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] into the symmetric tensor, products as given.
  Eigen::Matrix3d J;
  J << 6.25, 0.5, -0.25, 0.5, 6.25, 0.125, -0.25, 0.125, 12.0;
  EXPECT_EQ(m.body.inertia, J);
  EXPECT_EQ(m.sensors.sample_rate_hz, 250.0);
  EXPECT_EQ(m.sensors.force_noise_n, 1.0);
  EXPECT_EQ(m.sensors.encoder_bits, 17);
  // air_drag is switched off: two effects, in file order.
  ASSERT_EQ(m.effects.size(), 2u);
  EXPECT_STREQ(m.effects[0]->name(), "encoder_offset");
  EXPECT_STREQ(m.effects[1]->name(), "load_cell_gain");
  EXPECT_EQ(m.effect("air_drag"), nullptr);
}

TEST(RigReader, NameDefaultsToTheFileStem) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "bench rig .yaml", replace_first(kValidRig, "name: three-rod\n", ""));
  // Blanks at the ends of the stem are trimmed: the name goes on a "# rig:" line.
  EXPECT_EQ(io::read_rig(dir.path() / "bench rig .yaml").name, "bench rig");
}

TEST(RigReader, MissingFileNamesIt) {
  const test::TempDir dir("rigflex-rig-reader");
  try {
    io::read_rig(dir.path() / "none.yaml");
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "none.yaml").string());
    EXPECT_NE(e.reason().find("cannot open"), std::string::npos) << e.what();
  }
}

// --- rod count: rig.yaml has one place that fixes n (geometry.rods); the
// sensors block has no per-rod entries, so the mismatches a rig file can hold
// are per-rod effect parameters with another count.

TEST(RigReader, TwoRodsAreNotARig) {
  const std::string two = replace_first(kValidRig,
                                  "    - upper: [-0.2, -0.3464, 1.0]\n      lower: [-0.2, -0.3464, 0.0]\n"
                                  "      length: 1.0\n      encoder_axis: [0, 1, 0]\n",
                                  "");
  // A block list's line is that of its first entry.
  expect_error(two, "    - upper: [0.4", "geometry.rods", "3 or 4 rods (got 2)");
}

TEST(RigReader, EncoderOffsetWithAnotherRodCount) {
  const std::string bad = replace_first(kValidRig, "alpha: [0.001, 0.002, 0.003]", "alpha: [0.001, 0.002]");
  expect_error(bad, "  encoder_offset:", "effects.encoder_offset.alpha", "list of 3 numbers");
}

TEST(RigReader, LoadCellGainWithAnotherRodCount) {
  const std::string bad = replace_first(kValidRig, "gain: [1.0, 1.01, 0.99]", "gain: [1.0, 1.01, 0.99, 1.0]");
  expect_error(bad, "  load_cell_gain:", "effects.load_cell_gain.gain", "list of 3 numbers");
}

TEST(RigReader, RodLengthErrorWithAnotherRodCount) {
  // A block list: the error names the line where the list starts.
  const std::string bad = std::string(kValidRig) + "  rod_length_error:\n    delta:\n      - 0.001\n      - 0.002\n";
  expect_error(bad, "      - 0.001", "effects.rod_length_error.delta", "list of 3 numbers");
}

TEST(RigReader, JointPositionErrorWithAnotherRodCount) {
  const std::string bad = std::string(kValidRig) + "  joint_position_error: {upper: [[0, 0, 0.001], [0, 0, 0]]}\n";
  expect_error(bad, "  joint_position_error:", "effects.joint_position_error.upper", "one [x, y, z] per rod (3), got 2");
}

// --- geometry

TEST(RigReader, NonUnitEncoderAxis) {
  const std::string bad = replace_first(kValidRig, "encoder_axis: [-0.5, 0.8660254037844386, 0]", "encoder_axis: [-1, 1, 0]");
  expect_error(bad, "encoder_axis: [-1, 1, 0]", "geometry.rods[2].encoder_axis", "unit vector");
}

TEST(RigReader, NonHorizontalEncoderAxis) {
  // Unit, but tilted out of the horizontal plane.
  const std::string bad = replace_first(kValidRig, "encoder_axis: [0, 1, 0]", "encoder_axis: [0, 0.6, 0.8]");
  expect_error(bad, "encoder_axis: [0, 0.6, 0.8]", "geometry.rods[3].encoder_axis", "horizontal");
}

TEST(RigReader, RodThatCannotReach) {
  // |A - P - B| = 1 m at the nominal pose; 1.2 m is 20 % off, beyond the 5 % allowed.
  const std::string bad = replace_first(kValidRig, "      length: 1.0\n      encoder_axis: [-0.5",
                                  "      length: 1.2\n      encoder_axis: [-0.5");
  expect_error(bad, "length: 1.2", "geometry.rods[2].length", "cannot reach");
}

TEST(RigReader, RodGeometryKeysNameTheRod) {
  const std::string bad = replace_first(kValidRig, "lower: [-0.2, -0.3464, 0.0]", "lower: [-0.2, -0.3464]");
  expect_error(bad, "lower: [-0.2, -0.3464]", "geometry.rods[3].lower", "3 numbers");
}

// --- body

TEST(RigReader, NegativeMass) {
  const std::string bad = replace_first(kValidRig, "mass: 100.0", "mass: -100.0");
  expect_error(bad, "mass: -100.0", "body.mass", "must be positive");
}

TEST(RigReader, InertiaNotPositiveDefinite) {
  // Jxy = 7 > Jxx = Jyy = 6.25: principal moments -0.75, 12 and 13.25.
  const std::string bad = replace_first(kValidRig, "inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]",
                                  "inertia: [6.25, 6.25, 12.0, 7, 0, 0]");
  expect_error(bad, "inertia: [6.25, 6.25, 12.0, 7, 0, 0]", "body.inertia", "positive definite");
}

TEST(RigReader, InertiaNoBodyCanHave) {
  // Positive definite, but Jzz > Jxx + Jyy: no mass distribution has it.
  const std::string bad = replace_first(kValidRig, "inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]",
                                  "inertia: [1, 1, 5, 0, 0, 0]");
  expect_error(bad, "inertia: [1, 1, 5, 0, 0, 0]", "body.inertia", "triangle inequality");
}

TEST(RigReader, BodyUncertaintyDefaultsToAStaticReferenceAndARigidIdentification) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", kValidRig);
  const rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  EXPECT_EQ(m.body_uncertainty.cog, rig::Vec3(0.003, 0.003, 0.007));
  EXPECT_FALSE(m.body_uncertainty.inertia.has_value());
  // 10 % of the mean principal moment (6.25 + 6.25 + 12) / 3, products too.
  for (double s : m.body_uncertainty.inertia_std(m.body)) EXPECT_DOUBLE_EQ(s, 0.1 * 24.5 / 3.0);
}

TEST(RigReader, ReadsTheBodyUncertainty) {
  const std::string text = replace_first(kValidRig, "  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]\n",
                                         "  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]\n"
                                         "  uncertainty: {cog: [0.001, 0.002, 0], inertia: [0.5, 0.6, 0.7, 0, 0.1, 0.2]}\n");
  const rig::RigModel m = rig_of(text);
  EXPECT_EQ(m.body_uncertainty.cog, rig::Vec3(0.001, 0.002, 0.0));
  ASSERT_TRUE(m.body_uncertainty.inertia.has_value());
  EXPECT_EQ(*m.body_uncertainty.inertia, (std::array<double, 6>{0.5, 0.6, 0.7, 0.0, 0.1, 0.2}));
}

TEST(RigReader, NegativeBodyUncertainty) {
  const std::string bad = replace_first(kValidRig, "  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]\n",
                                        "  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]\n"
                                        "  uncertainty: {cog: [0.001, -0.002, 0.004]}\n");
  expect_error(bad, "uncertainty: {cog", "body.uncertainty.cog", ">= 0");
}

TEST(RigReader, UnknownKeyInTheBodyUncertainty) {
  const std::string bad = replace_first(kValidRig, "  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]\n",
                                        "  inertia: [6.25, 6.25, 12.0, 0.5, -0.25, 0.125]\n"
                                        "  uncertainty: {mass: 0.1}\n");
  expect_error(bad, "uncertainty: {mass", "body.uncertainty.mass", "unknown key");
}

// --- the rods block: nominal axial stiffness and damping, plain keys

std::string with_rods(const std::string& block) { return replace_first(kValidRig, "sensors:\n", block + "sensors:\n"); }

TEST(RigReader, RodsAreRigidAndUndampedWithoutTheBlock) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", kValidRig);
  const rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  EXPECT_TRUE(m.rods.stiffness.empty());
  EXPECT_TRUE(m.rods.damping.empty());
}

TEST(RigReader, ReadsTheRodsStiffnessAndDampingOnePerRodOrOneForAll) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", with_rods("rods:\n  stiffness: [2.0e7, 2.1e7, 1.9e7]\n  damping: 300\n"));
  const rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  EXPECT_EQ(m.rods.stiffness, (std::vector<double>{2.0e7, 2.1e7, 1.9e7}));
  EXPECT_EQ(m.rods.damping, (std::vector<double>{300.0, 300.0, 300.0}));
}

TEST(RigReader, RodsStiffnessFromYoungsModulusAndArea) {
  // EA / L with L = 1 m for every rod of kValidRig.
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", with_rods("rods: {youngs_modulus: 2.1e11, area: [1e-4, 2e-4, 1e-4]}\n"));
  const rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  EXPECT_EQ(m.rods.stiffness, (std::vector<double>{2.1e7, 4.2e7, 2.1e7}));
}

TEST(RigReader, RodsStiffnessGivenTwoWaysIsRefused) {
  const std::string bad = with_rods("rods:\n  stiffness: 2.0e7\n  youngs_modulus: 2.1e11\n  area: 1e-4\n");
  expect_error(bad, "  youngs_modulus", "rods", "not both");
}

TEST(RigReader, RodsStiffnessWithAnotherRodCount) {
  expect_error(with_rods("rods:\n  stiffness: [2.0e7, 2.0e7]\n"), "  stiffness", "rods.stiffness", "3");
}

TEST(RigReader, RodsStiffnessMustBePositive) {
  expect_error(with_rods("rods:\n  stiffness: [2.0e7, 0, 2.0e7]\n"), "  stiffness", "rods.stiffness", "positive");
}

TEST(RigReader, RodsDampingMustNotBeNegative) {
  expect_error(with_rods("rods:\n  damping: -1\n"), "  damping", "rods.damping", ">= 0");
}

TEST(RigReader, ReadsHowWellTheRodsStiffnessIsKnown) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", with_rods("rods:\n  stiffness: 2.0e7\n  uncertainty: {stiffness: 0.15}\n"));
  EXPECT_EQ(io::read_rig(dir.path() / "rig.yaml").rods.stiffness_uncertainty, 0.15);
  test::write_text(dir.path() / "rig.yaml", with_rods("rods:\n  stiffness: 2.0e7\n"));
  EXPECT_EQ(io::read_rig(dir.path() / "rig.yaml").rods.stiffness_uncertainty, 0.0);  // held as given
}

TEST(RigReader, RodsStiffnessUncertaintyNeedsAStiffnessAndARelativeValue) {
  expect_error(with_rods("rods:\n  damping: 10\n  uncertainty: {stiffness: 0.1}\n"), "  uncertainty",
               "rods.uncertainty.stiffness", "rigid rods");
  expect_error(with_rods("rods:\n  stiffness: 2.0e7\n  uncertainty: {stiffness: 1.5}\n"), "  uncertainty",
               "rods.uncertainty.stiffness", "[0, 1)");
  expect_error(with_rods("rods:\n  stiffness: 2.0e7\n  uncertainty: {damping: 0.1}\n"), "  uncertainty",
               "rods.uncertainty.damping", "unknown key");
}

TEST(RigReader, UnknownKeyInTheRodsBlock) {
  expect_error(with_rods("rods:\n  colour: 3\n"), "  colour", "rods.colour", "unknown key");
}

TEST(RigReader, RodsTooSoftToHoldTheBodyNameTheirStiffness) {
  // What the commands report when no equilibrium is found with these rods.
  const test::TempDir dir("rigflex-rig-reader");
  const std::string text = with_rods("rods:\n  stiffness: 10\n");
  const auto file = dir.path() / "rig.yaml";
  test::write_text(file, text);
  const io::InputError e = io::no_equilibrium_error(file, io::read_rig(file), "no static equilibrium");
  EXPECT_EQ(e.key(), "rods.stiffness");
  EXPECT_EQ(e.line(), line_of(text, "  stiffness: 10"));
  EXPECT_NE(e.reason().find("too soft"), std::string::npos) << e.what();
}

// --- keys and effects

TEST(RigReader, UnknownTopLevelKey) {
  const std::string bad = replace_first(kValidRig, "body:\n", "colour: red\nbody:\n");
  expect_error(bad, "colour: red", "colour", "unknown key");
}

TEST(RigReader, UnknownKeyInASection) {
  const std::string bad = replace_first(kValidRig, "load_cell: {noise: 1.0}", "load_cell: {noise: 1.0, drift: 2}");
  expect_error(bad, "load_cell: {noise", "sensors.load_cell.drift", "unknown key");
}

TEST(RigReader, UnknownEffectName) {
  // Refused even when switched off: a misspelt name is a mistake either way.
  const std::string bad = std::string(kValidRig) + "  rod_complience: {stiffness: 1.0e7, enabled: false}\n";
  const io::InputError e = rig_error_of(bad);
  EXPECT_EQ(e.line(), line_of(bad, "rod_complience"));
  EXPECT_EQ(e.key(), "effects.rod_complience");
  EXPECT_NE(e.reason().find("unknown effect 'rod_complience'"), std::string::npos) << e.what();
  EXPECT_NE(e.reason().find("rod_compliance"), std::string::npos) << e.what();  // lists the known names
}

TEST(RigReader, EffectMissingARequiredParameter) {
  const std::string bad = std::string(kValidRig) + "  rod_length_error: {enabled: true}\n";
  expect_error(bad, "rod_length_error", "effects.rod_length_error.delta", "missing required key");
}

TEST(RigReader, EffectMissingAllOfItsOptions) {
  const std::string bad = std::string(kValidRig) + "  joint_friction: {regularization: 0.01}\n";
  expect_error(bad, "joint_friction", "effects.joint_friction", "needs 'viscous'");
}

TEST(RigReader, EffectParameterOfTheWrongType) {
  const std::string bad = std::string(kValidRig) + "  joint_friction: {viscous: 0.1, joints: middle}\n";
  expect_error(bad, "joint_friction", "effects.joint_friction.joints", "both, upper or lower");
}

// Every number of an effect is held to its physical range, absolute or
// scaled by the rig (rig/effect_ranges.hpp), at the number's own line.
TEST(RigReader, EffectParameterOutOfRange) {
  expect_error(std::string(kValidRig) + "  rod_mass:\n    mass: -2.0\n", "mass: -2.0", "effects.rod_mass.mass",
               "'-2.0' kg is outside the physical range [0, 1 m_body]");
  expect_error(std::string(kValidRig) + "  rod_length_error:\n    delta: [0.001, 0.9, 0.0]\n", "delta: [0.001",
               "effects.rod_length_error.delta", "'0.9' m is outside the physical range [-0.2 L, 0.2 L]");
  expect_error(std::string(kValidRig) + "  joint_position_error:\n    upper: [[0, 0, 0], [0, 0, 0], [0, 0.58, 0]]\n",
               "upper: [[0", "effects.joint_position_error.upper", "'0.58' m is outside the physical range");
  expect_error(replace_first(kValidRig, "alpha: [0.001, 0.002", "alpha: [0.001, 5.0"), "alpha: [0.001, 5.0",
               "effects.encoder_offset.alpha", "'5.0' rad is outside the physical range [-0.5, 0.5]");
  expect_error(std::string(kValidRig) + "  rod_compliance: {stiffness: 1.0}\n", "rod_compliance: {stiffness",
               "effects.rod_compliance.stiffness", "more than a fifth of its length");
  expect_error(std::string(kValidRig) + "  joint_position_error: {upper: [[0, 0, 0], [0, .nan, 0], [0, 0, 0]]}\n",
               "joint_position_error: {upper", "effects.joint_position_error.upper", "expected a finite number");
}

// An effect's `uncertainty` states how well the model knows its values:
// read beside the effect (which parses without it), one item per number or
// per rod, and refused where it cannot be refitted.
TEST(RigReader, EffectUncertaintyIsReadBesideTheEffect) {
  const std::string text = replace_first(kValidRig, "  load_cell_gain: {gain: [1.0, 1.01, 0.99]}",
                                         "  load_cell_gain: {gain: [1.0, 1.01, 0.99], uncertainty: {gain: [0.01, 0.02, "
                                         "0.03], offset: 2.0}}\n  rod_mass: {mass: 1.5, uncertainty: {mass: 0.3}}");
  const rig::RigModel m = rig_of(text);
  ASSERT_EQ(m.effects.size(), 3u);
  ASSERT_EQ(m.effect_uncertainty.size(), 2u);
  const rig::EffectUncertainty& g = m.effect_uncertainty[0];
  EXPECT_EQ(g.effect, "load_cell_gain");
  ASSERT_EQ(g.items.size(), 4u);  // a gain per rod, one common offset
  EXPECT_EQ(g.items[2].name(), "gain[2]");
  EXPECT_EQ(g.items[2].sigma, 0.03);
  EXPECT_EQ(g.items[3].name(), "offset");
  EXPECT_EQ(g.items[3].unit, "N");
  EXPECT_EQ(m.effect_uncertainty[1].items[0].name(), "mass");
  // An effects file that states the effect again replaces its uncertainty too.
  const std::string again =
      replace_first(text, "  rod_mass: {mass: 1.5, uncertainty: {mass: 0.3}}", "  rod_mass: {mass: 1.5}");
  EXPECT_EQ(rig_of(again).effect_uncertainty.size(), 1u);
}

// A frame states one relative deviation of its stiffness: one item, in %,
// refitted as a factor on the built frame (rig::stiffened).
TEST(RigReader, AFramesStiffnessUncertainty) {
  const std::string text = std::string(kValidRig) +
                           "  carrying_frame_flexibility:\n    joint_compliance: {translation: [1e-7, 1e-7, 1e-8]}\n"
                           "    uncertainty: {stiffness: 0.15}\n";
  const rig::RigModel m = rig_of(text);
  ASSERT_EQ(m.effect_uncertainty.size(), 1u);
  const rig::EffectUncertainty& u = m.effect_uncertainty[0];
  EXPECT_EQ(u.effect, "carrying_frame_flexibility");
  EXPECT_TRUE(u.frame_stiffness);
  ASSERT_EQ(u.items.size(), 1u);
  EXPECT_EQ(u.items[0].name(), "stiffness");
  EXPECT_EQ(u.items[0].unit, "%");
  EXPECT_DOUBLE_EQ(u.items[0].sigma, 15.0);
}

// A frame that states no uncertainty has its stiffness known to
// rig::kFrameStiffnessUncertainty; {stiffness: 0} holds it as given. Other
// effects without one are held.
TEST(RigReader, AFramesStiffnessUncertaintyByDefault) {
  const std::string frame =
      "  fixed_frame_flexibility:\n    joint_compliance: {joints: [[1e-7, 1e-7, 1e-8], [1e-7, 1e-7, 1e-8], "
      "[1e-7, 1e-7, 1e-8]]}\n";
  const rig::RigModel m = rig_of(std::string(kValidRig) + "  rod_mass: {mass: 1.5}\n" + frame);
  ASSERT_EQ(m.effect_uncertainty.size(), 1u);
  const rig::EffectUncertainty& u = m.effect_uncertainty[0];
  EXPECT_EQ(u.effect, "fixed_frame_flexibility");
  EXPECT_TRUE(u.frame_stiffness);
  ASSERT_EQ(u.items.size(), 1u);
  EXPECT_DOUBLE_EQ(u.items[0].sigma, 100.0 * rig::kFrameStiffnessUncertainty);
  const rig::RigModel held = rig_of(std::string(kValidRig) + frame + "    uncertainty: {stiffness: 0}\n");
  EXPECT_TRUE(held.effect_uncertainty.empty());
  EXPECT_TRUE(std::any_of(held.effects.begin(), held.effects.end(),
                          [](const auto& e) { return std::string(e->name()) == "fixed_frame_flexibility"; }));
}

TEST(RigReader, EffectUncertaintyThatCannotBeRefitted) {
  const std::string rig = kValidRig;
  expect_error(rig + "  rod_mass: {mass: 1.5, uncertainty: {weight: 0.3}}\n", "rod_mass",
               "effects.rod_mass.uncertainty.weight", "not a parameter of rod_mass");
  expect_error(rig + "  rod_mass: {mass: 1.5, uncertainty: {mass: 0}}\n", "rod_mass",
               "effects.rod_mass.uncertainty.mass", "positive standard deviation");
  expect_error(rig + "  rod_mass: {mass: 1.5, uncertainty: {mass: [0.1, 0.1]}}\n", "rod_mass",
               "effects.rod_mass.uncertainty.mass", "one standard deviation per rod (3)");
  expect_error(rig + "  rod_mass: {mass: 1.5, uncertainty: 0.3}\n", "rod_mass", "effects.rod_mass.uncertainty",
               "mapping of parameter key");
  expect_error(
      rig + "  joint_position_error: {upper: [[0, 0, 0], [0, 0, 0], [0, 0, 0]], uncertainty: {upper: 0.001}}\n",
      "joint_position_error", "effects.joint_position_error.uncertainty.upper", "held as given");
  expect_error(rig +
                   "  rod_length_error: {delta: 0.001, uncertainty: {delta: [0.001, 0.001, 0.001]}}\n"
                   "  fixed_frame_flexibility:\n    joint_compliance: {joints: [[1e-7, 1e-7, 1e-8], [1e-7, 1e-7, "
                   "1e-8], [1e-7, 1e-7, 1e-8]]}\n    uncertainty: {zeta: 0.01}\n",
               "    uncertainty: {zeta", "effects.fixed_frame_flexibility.uncertainty",
               "held as given but for one factor on its stiffness");
  expect_error(rig +
                   "  fixed_frame_flexibility:\n    joint_compliance: {joints: [[1e-7, 1e-7, 1e-8], [1e-7, 1e-7, "
                   "1e-8], [1e-7, 1e-7, 1e-8]]}\n    uncertainty: {stiffness: 1.0}\n",
               "    uncertainty: {stiffness", "effects.fixed_frame_flexibility.uncertainty.stiffness",
               "must lie in [0, 1): a relative standard deviation");
  expect_error(rig +
                   "  fixed_frame_flexibility:\n    joint_compliance: {joints: [[1e-7, 1e-7, 1e-8], [1e-7, 1e-7, "
                   "1e-8], [1e-7, 1e-7, 1e-8]]}\n    uncertainty: {stiffness: -0.1}\n",
               "    uncertainty: {stiffness", "effects.fixed_frame_flexibility.uncertainty.stiffness",
               "must lie in [0, 1)");
  // A key the effect does not give, and which has no default, has nothing to refit.
  expect_error(rig + "  rod_compliance: {stiffness: 1e7, uncertainty: {youngs_modulus: 1e9}}\n", "rod_compliance",
               "effects.rod_compliance.uncertainty.youngs_modulus", "gives no 'youngs_modulus' to refit");
}

TEST(RigReader, FrameModelThatDoesNotExist) {
  const std::string bad =
      std::string(kValidRig) + "  fixed_frame_flexibility:\n    model: no-such-frame.yaml\n    interface: upper_joints\n";
  expect_error(bad, "model: no-such-frame.yaml", "effects.fixed_frame_flexibility.model", "no such file");
}

// --- the rig's name goes on a "# rig: name" line of every measurement file

TEST(RigReader, NameWithALineBreak) {
  const std::string bad = replace_first(kValidRig, "name: three-rod", "name: \"three\\nrod\"");
  expect_error(bad, "name:", "name", "line break");
}

TEST(RigReader, NameWithAControlCharacter) {
  const std::string bad = replace_first(kValidRig, "name: three-rod", "name: \"three\\trod\"");
  expect_error(bad, "name:", "name", "control characters");
}

TEST(RigReader, NameWithBlanksAtTheEnds) {
  for (const char* name : {"\" three-rod\"", "\"three-rod \""}) {
    const std::string bad = replace_first(kValidRig, "name: three-rod", std::string("name: ") + name);
    expect_error(bad, "name:", "name", "blank");
  }
}

TEST(RigReader, EmptyName) {
  const std::string bad = replace_first(kValidRig, "name: three-rod", "name: \"\"");
  expect_error(bad, "name:", "name", "empty");
}

// Frames given by their joint compliance (rig/joint_compliance.hpp), as
// `rigflex diagnose` writes them, and the checks of such blocks.
TEST(RigReader, FramesByJointCompliance) {
  const std::string fixed = std::string(kValidRig) +
                            "  fixed_frame_flexibility:\n    joint_compliance:\n      joints: [[1e-6, 2e-6, 3e-7], "
                            "[1e-6, 2e-6, 3e-7], [1e-6, 2e-6, 3e-7]]\n      sway: [1e-6, 0]\n      twist: 1e-6\n"
                            "  carrying_frame_flexibility:\n    joint_compliance: {translation: [1e-6, 1e-6, 5e-7], "
                            "rocking: [1e-6, 2e-6]}\n";
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", fixed);
  const rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  EXPECT_NE(m.effect("fixed_frame_flexibility"), nullptr);
  EXPECT_NE(m.effect("carrying_frame_flexibility"), nullptr);
  expect_error(replace_first(fixed, "[1e-6, 2e-6, 3e-7], [1e-6", "[1e-6, -2e-6, 3e-7], [1e-6"), "      joints:",
               "effects.fixed_frame_flexibility.joint_compliance.joints", ">= 0");
  expect_error(replace_first(fixed, "      twist: 1e-6", "      spin: 1e-6"), "      spin:",
               "effects.fixed_frame_flexibility.joint_compliance.spin", "");
}

// An effect given twice in one rig file is an error, not the last one winning.
TEST(RigReader, AnEffectGivenTwiceIsRefused) {
  const std::string twice = std::string(kValidRig) + "  encoder_offset: {alpha: 0.0, beta: 0.0}\n";
  expect_error(twice, "  encoder_offset: {alpha: 0.0", "effects.encoder_offset", "given twice");
}

// An effects file replaces the model's effect of the same name; `enabled: false` removes it.
TEST(RigReader, EffectsFilesReplaceByName) {
  const test::TempDir dir("rigflex-rig-reader");
  test::write_text(dir.path() / "rig.yaml", kValidRig);
  rig::RigModel m = io::read_rig(dir.path() / "rig.yaml");
  const size_t before = m.effects.size();
  test::write_text(dir.path() / "more.yaml", "effects:\n  rod_mass: {mass: 2.0}\n  encoder_offset: {enabled: false}\n");
  io::add_effects(m, dir.path() / "more.yaml");
  EXPECT_EQ(m.effects.size(), before);  // one added, one removed
  EXPECT_NE(m.effect("rod_mass"), nullptr);
  EXPECT_EQ(m.effect("encoder_offset"), nullptr);
  test::write_text(dir.path() / "bad.yaml", "rod_mass: {mass: 2.0}\n");
  EXPECT_THROW(io::add_effects(m, dir.path() / "bad.yaml"), io::InputError);
}



// --- reading is pure: frames are reduced by rig::resolve_frames, a step of its own

TEST(RigSpec, ReadingReducesNoFrameAndResolvingGivesWhatReadRigGives) {
  const std::filesystem::path file = std::filesystem::path(RIGFLEX_SOURCE_DIR) / "examples/large-rig/rig.yaml";
  const rig::RigSpec spec = io::read_rig_spec(file);
  ASSERT_EQ(spec.pending_frames(), 1);  // the fixed frame, a frame model to reduce
  const auto* pending = dynamic_cast<const rig::PendingFrame*>(spec.rig.effect("fixed_frame_flexibility"));
  ASSERT_NE(pending, nullptr);
  EXPECT_TRUE(pending->source().fixed);
  EXPECT_FALSE(pending->source().reduced.has_value());
  EXPECT_FALSE(pending->source().model.nodes.empty());
  // A rig still holding a pending frame cannot be assembled.
  EXPECT_THROW(rig::RigSystem{spec.rig}, std::logic_error);

  std::vector<std::string> stages;
  const rig::RigModel resolved = rig::resolve_frames(spec, [&](const std::string& s) { stages.push_back(s); });
  EXPECT_FALSE(stages.empty());
  EXPECT_EQ(rig::RigSpec{resolved}.pending_frames(), 0);
  const rig::RigModel direct = io::read_rig(file);
  ASSERT_EQ(resolved.effects.size(), direct.effects.size());
  for (size_t i = 0; i < direct.effects.size(); ++i) EXPECT_STREQ(resolved.effects[i]->name(), direct.effects[i]->name());
  const auto* a = dynamic_cast<const rig::FixedFrameFlexibility*>(resolved.effect("fixed_frame_flexibility"));
  const auto* b = dynamic_cast<const rig::FixedFrameFlexibility*>(direct.effect("fixed_frame_flexibility"));
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  // The same reduction of the same model: bit for bit.
  EXPECT_EQ(a->model().K, b->model().K);
  EXPECT_EQ(a->model().M, b->model().M);
  EXPECT_EQ(a->model().joint_row, b->model().joint_row);
}

// A frame is held to the memory limit before its reduction's assembly (and
// each factorization: FrameReduction.EachFactorizationIsHeldToTheMemoryLimit):
// an error of the rig file's model key, telling the user what to do.
TEST(RigSpec, AFrameTooLargeForTheMemoryIsRefusedBeforeTheWork) {
  const std::filesystem::path file = std::filesystem::path(RIGFLEX_SOURCE_DIR) / "examples/large-rig/rig.yaml";
  const rig::RigSpec spec = io::read_rig_spec(file);
  const auto* pending = dynamic_cast<const rig::PendingFrame*>(spec.rig.effect("fixed_frame_flexibility"));
  ASSERT_NE(pending, nullptr);
  const double assembly = fe::assembly_size(pending->source().model).bytes;
  double largest_factor = 0;
  rig::FrameResolveOptions heard;
  heard.analyzed = [&](const linalg::FactorStatistics& s) {
    largest_factor = std::max(largest_factor, s.factor_bytes_estimate);
  };
  rig::resolve_frames(spec, heard);
  ASSERT_GT(largest_factor, 0.0);

  auto refusal = [&](double limit) -> std::string {
    rig::FrameResolveOptions o;
    o.max_bytes = limit;
    try {
      rig::resolve_frames(spec, o);
    } catch (const rig::SpecError& e) {
      EXPECT_EQ(e.where().key, "effects.fixed_frame_flexibility.model") << e.what();
      EXPECT_NE(e.reason().find("rigflex reduce"), std::string::npos) << e.what();
      return e.reason();
    }
    return "";
  };
  EXPECT_NE(refusal(0.5 * assembly).find("to assemble, above the limit"), std::string::npos);
  EXPECT_EQ(refusal(2 * std::max(assembly, largest_factor)), "");
}

TEST(RigSpec, AFrameThatCannotBeReducedIsNamedWhenResolved) {
  test::TempDir dir("rigflex-rig-spec");
  std::filesystem::copy_file(std::filesystem::path(RIGFLEX_SOURCE_DIR) / "examples/beam-frame/model.yaml",
                             dir.path() / "frame.yaml");
  const std::string text =
      std::string(kValidRig) + "  fixed_frame_flexibility:\n    model: frame.yaml\n    interface: no_such_set\n";
  const std::filesystem::path file = dir.path() / "rig.yaml";
  test::write_text(file, text);
  const rig::RigSpec spec = io::read_rig_spec(file);  // read: the set is looked up only when reducing
  EXPECT_EQ(spec.pending_frames(), 1);
  try {
    rig::resolve_frames(spec);
    ADD_FAILURE() << "no error for an interface set that does not exist";
  } catch (const rig::SpecError& e) {
    EXPECT_EQ(e.where().file, file.string());
    EXPECT_EQ(e.where().line, line_of(text, "model: frame.yaml"));
    EXPECT_EQ(e.where().key, "effects.fixed_frame_flexibility.model");
    EXPECT_NE(e.reason().find("no_such_set"), std::string::npos) << e.what();
  }
  // read_rig reports it as the InputError it always was.
  try {
    io::read_rig(file);
    ADD_FAILURE() << "no error from read_rig";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line(), line_of(text, "model: frame.yaml"));
    EXPECT_EQ(e.key(), "effects.fixed_frame_flexibility.model");
    EXPECT_NE(e.reason().find("no_such_set"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rigflex
