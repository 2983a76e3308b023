// Element sets by geometry or id in a model file (`element_sets:`) and what
// `assign:` gives them: a thicker band of a plate chosen by a box gives the
// modes of the same plate built from three patches (the same mesh, to
// round-off); `mass: none` removes the set's mass; faults name line and key.
#include <gtest/gtest.h>

#include <string>

#include "fe/mass_properties.hpp"
#include "io/input_error.hpp"
#include "io/model_reader.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/input_errors.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

const std::string kPlate = R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
shell_sections:
  thin: {material: steel, thickness: 0.01}
  thick: {material: steel, thickness: 0.02}
supports:
  - {line: [[0, 0, 0], [0, 1, 0]], dofs: all}
)";

Eigen::VectorXd plate_modes(const std::string& text) {
  return test::checked_modal_analysis(io::parse_model(text, "plate.yaml").model, 8).result.frequencies_hz();
}

TEST(ElementSets, ABandChosenByABoxTakesItsSection) {
  const Eigen::VectorXd patches = plate_modes(kPlate + R"(shell_patches:
  - {id: a, corners: [[0, 0, 0], [0.75, 0, 0], [0.75, 1, 0], [0, 1, 0]], divisions: [3, 4], section: thin}
  - {id: b, corners: [[0.75, 0, 0], [1.25, 0, 0], [1.25, 1, 0], [0.75, 1, 0]], divisions: [2, 4], section: thick}
  - {id: c, corners: [[1.25, 0, 0], [2, 0, 0], [2, 1, 0], [1.25, 1, 0]], divisions: [3, 4], section: thin}
)");
  const std::string banded = kPlate + R"(shell_patches:
  - {id: p, corners: [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], divisions: [8, 4], section: thin}
element_sets:
  band: {box: [[0.75, -1, -1], [1.25, 2, 1]]}
assign:
  - {set: band, section: thick}
)";
  const Eigen::VectorXd sets = plate_modes(banded);
  for (Eigen::Index k = 0; k < 8; ++k) EXPECT_NEAR(sets(k) / patches(k), 1.0, 1e-9) << "mode " << k + 1;
  const io::ModelFile f = io::parse_model(banded, "plate.yaml");
  int thick = 0;
  for (const fe::ShellElement& s : f.model.shells) thick += s.section == "thick";
  EXPECT_EQ(thick, 8);  // 2 x 4 elements with every node in the box
}

TEST(ElementSets, IdsAndMassKinds) {
  const std::string text = kPlate + R"(shell_patches:
  - {id: p, corners: [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], divisions: [2, 1], section: thin}
members:
  - {id: rib, from: [0, 1, 0], to: [2, 1, 0], elements: 2, section: bar}
beam_sections:
  bar: {material: steel, shape: rectangle, width: 0.02, height: 0.04}
element_sets:
  rib: {line: [[0, 1, 0], [2, 1, 0]]}
assign:
  - {set: rib, mass: none}
)";
  const io::ModelFile f = io::parse_model(text, "plate.yaml");
  for (const fe::BeamElement& b : f.model.beams) EXPECT_EQ(b.mass, fe::MassKind::None);
  for (const fe::ShellElement& s : f.model.shells) EXPECT_EQ(s.mass, fe::MassKind::Consistent);  // not on the line
  EXPECT_NEAR(fe::mass_properties(f.model).mass, 2 * 1 * 0.01 * 7850, 1e-9);
}

TEST(ElementSets, FaultsNameLineAndKey) {
  const std::string plate = kPlate + R"(shell_patches:
  - {id: p, corners: [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], divisions: [2, 1], section: thin}
)";
  struct Case {
    std::string tail;
    int line;
    std::string key, fragment;
  };
  const Case cases[] = {
      {"element_sets:\n  s: {near: [[9, 9, 9], 0.1]}\n", 11, "near", "no node selected"},
      {"element_sets:\n  s: {box: [[-1, -1, -1], [0.5, 2, 1]]}\n", 11, "element_sets", "no element has all its nodes"},
      {"element_sets:\n  s: {elements: [nope]}\n", 11, "elements", "no beam, shell or solid 'nope'"},
      {"element_sets:\n  s: {box: [[-1, -1, -1], [3, 2, 1]]}\nassign:\n  - {set: s, section: steel}\n", 13, "section",
       "no shell section 'steel'"},
      {"assign:\n  - {set: t, mass: none}\n", 11, "set", "element set 't' does not exist"},
  };
  for (const Case& c : cases) {
    const io::InputError e = test::input_error_of([&] { io::parse_model(plate + c.tail, "plate.yaml"); }, c.tail);
    EXPECT_EQ(e.line(), c.line) << c.fragment << ": " << e.what();
    EXPECT_EQ(e.key(), c.key) << c.fragment << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rigflex
