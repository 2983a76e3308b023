// io::load_yaml and io::range_problem: what every YAML reader refuses
// before reading a key, and the physical-range messages.
#include <gtest/gtest.h>

#include <string>

#include "io/input_error.hpp"
#include "io/physical_range.hpp"
#include "io/yaml_document.hpp"

namespace rigflex {
namespace {

io::InputError error_of(const std::string& text, long max_nodes = 10'000'000) {
  try {
    io::load_yaml(text, "f.yaml", max_nodes);
  } catch (const io::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return io::InputError("", 0, "", "");
}

TEST(LoadYaml, AKeyTwiceIsNamedWithItsPathAndBothLines) {
  const auto e = error_of("geometry:\n  rods:\n    - {upper: [0, 0, 1]}\n    - {upper: [0, 0, 1], upper: [1, 0, 1]}\n");
  EXPECT_EQ(e.key(), "geometry.rods[2].upper");
  EXPECT_EQ(e.line(), 4);
  EXPECT_NE(e.reason().find("first at line 4, column 8"), std::string::npos) << e.what();
}

TEST(LoadYaml, TheSameKeyInTwoMappingsIsFine) {
  EXPECT_NO_THROW(io::load_yaml("a: {x: 1}\nb: {x: 2}\nc: [{x: 1}, {x: 2}]\n", "f.yaml"));
}

TEST(LoadYaml, RefusesAListAsAKeyNotUtf8AndAliasBombs) {
  EXPECT_NE(error_of("? [a, b]\n: 1\n").reason().find("a key must be a plain name"), std::string::npos);
  const auto latin1 = error_of("name: caf\xe9\n");
  EXPECT_EQ(latin1.line(), 1);
  EXPECT_NE(latin1.reason().find("not UTF-8 at column 10 (byte 0xE9)"), std::string::npos) << latin1.what();
  // Overlong encoding of '/' and a UTF-16 surrogate are not UTF-8 either.
  EXPECT_NE(error_of("a: \xc0\xaf\n").reason().find("not UTF-8"), std::string::npos);
  EXPECT_NE(error_of("a: \xed\xa0\x80\n").reason().find("not UTF-8"), std::string::npos);
  EXPECT_NO_THROW(io::load_yaml("name: caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x94\xa7\n", "f.yaml"));
  // The root, a (a list of 3: 4 nodes) and b (a list of three copies of a: 13): 18, within 20, past 10.
  EXPECT_NO_THROW(io::load_yaml("a: &a [1, 2, 3]\nb: [*a, *a, *a]\n", "f.yaml", 20));
  EXPECT_NE(error_of("a: &a [1, 2, 3]\nb: [*a, *a, *a]\n", 10).reason().find("expands"), std::string::npos);
}

TEST(PhysicalRange, NamesHowFarAUnitSlipIs) {
  using io::range_problem;
  EXPECT_EQ(range_problem(2.1e11, io::ranges::youngs_modulus), "");
  EXPECT_EQ(range_problem(1e6, io::ranges::youngs_modulus), "");  // bounds inclusive
  EXPECT_EQ(range_problem(1e15, io::ranges::youngs_modulus), "");
  const std::string mpa = range_problem(2.1e5, io::ranges::youngs_modulus);
  EXPECT_NE(mpa.find("Young's modulus in Pa expected: 210000 is 6 orders of magnitude below steel"), std::string::npos)
      << mpa;
  EXPECT_NE(range_problem(-7850, io::ranges::density).find("must be positive"), std::string::npos);
  // Coordinates bound the magnitude and allow 0.
  EXPECT_EQ(range_problem(0.0, io::ranges::coordinate), "");
  EXPECT_EQ(range_problem(-999.0, io::ranges::coordinate), "");
  EXPECT_NE(range_problem(-3200.0, io::ranges::coordinate).find("3 orders of magnitude above"), std::string::npos);
}

// A lookup a reader did not check first throws yaml-cpp's own exceptions;
// guard_yaml turns them into the InputError of the file, with the key
// (an invalid node) or the line (a conversion) that yaml-cpp knows.
TEST(GuardYaml, YamlCppExceptionsBecomeInputErrorsOfTheFile) {
  const YAML::Node root = io::load_yaml("rods:\n  youngs_modulus: 2.1e11\nmass: heavy\n", "rig.yaml");
  try {
    io::guard_yaml("rig.yaml", [&] { return root["rods"]["area"]["x"].IsSequence(); });
    FAIL() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "rig.yaml");
    EXPECT_EQ(e.key(), "area") << e.what();
  }
  try {
    io::guard_yaml("rig.yaml", [&] { return root["mass"].as<double>(); });
    FAIL() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "rig.yaml");
    EXPECT_EQ(e.line(), 3) << e.what();
  }
  EXPECT_EQ(io::guard_yaml("rig.yaml", [&] { return root["rods"]["youngs_modulus"].as<double>(); }), 2.1e11);
}

}  // namespace
}  // namespace rigflex
