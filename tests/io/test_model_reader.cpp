// The model reader: valid input builds the model; bad input names file, line and key.
#include <gtest/gtest.h>

#include <algorithm>

#include "io/input_error.hpp"
#include "io/model_formats.hpp"
#include "io/model_reader.hpp"
#include "support/input_errors.hpp"
#include "support/temp_files.hpp"
#include "support/text_edits.hpp"

namespace rigflex {
namespace {

using test::replace_first;

const char* kValidModel = R"(name: frame
materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
beam_sections:
  col: {material: steel, shape: box, width: 0.2, height: 0.2, wall: 0.01}
  ib: {material: steel, shape: i-section, width: 0.2, height: 0.3, web_thickness: 0.01, flange_thickness: 0.015}
nodes:
  - [1, 0, 0, 0]
  - [2, 0, 0, 2]
members:
  - {id: top, from: [0, 0, 2], to: [3, 0, 2], elements: 3, section: ib}
supports:
  - {node: 1, dofs: all}
point_masses:
  - {id: tip, at: [3, 0, 2], mass: 100, inertia: [1, 1, 1, 0, 0, 0]}
beams:
  - {id: post, nodes: [1, 2], section: col}
)";

// Parses `text` and returns the error; fails the test if none is thrown.
io::InputError model_error_of(const std::string& text) {
  return test::input_error_of([&] { io::parse_model(text, "bad.yaml"); }, "the text:\n" + text);
}

TEST(ModelReader, ReadsAValidModel) {
  const io::ModelFile f = io::parse_model(kValidModel, "frame.yaml");
  EXPECT_EQ(f.name, "frame");
  EXPECT_EQ(f.model.nodes.size(), 5u);  // 2 given + 3 generated (one merged with node 2)
  EXPECT_EQ(f.model.beams.size(), 4u);
  EXPECT_EQ(f.model.point_masses.size(), 1u);
  EXPECT_EQ(f.model.supports.size(), 1u);
}

// read_model picks the format by extension, case-insensitively; an extension
// no format claims is read as the YAML model (the first format).
TEST(ModelFormats, ChosenByExtensionWithYamlAsDefault) {
  const auto& formats = io::model_formats();
  ASSERT_FALSE(formats.empty());
  EXPECT_EQ(&io::model_format_for("frame.yaml"), &formats.front());
  EXPECT_EQ(&io::model_format_for("FRAME.YML"), &formats.front());
  EXPECT_EQ(&io::model_format_for("frame.txt"), &formats.front());
  for (const auto& f : formats) {
    for (const auto& ext : f.extensions) EXPECT_EQ(&io::model_format_for("a" + ext), &f) << f.name << " " << ext;
  }
  test::TempDir dir("rigflex-model-formats");
  test::write_text(dir.path() / "frame.Yml", kValidModel);
  EXPECT_EQ(io::read_model(dir.path() / "frame.Yml").model.beams.size(), 4u);
  try {
    io::read_model(dir.path() / "absent.yaml");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "absent.yaml").string());
  }
}

TEST(ModelReader, MalformedYamlNamesTheLine) {
  const auto e = model_error_of("materials:\n  steel: {E: 1, nu: [0.3\n");
  EXPECT_EQ(e.file(), "bad.yaml");
  EXPECT_GT(e.line(), 0);
  EXPECT_NE(std::string(e.what()).find("malformed YAML"), std::string::npos);
}

TEST(ModelReader, UnknownKeyNamesLineAndKey) {
  const auto e = model_error_of(replace_first(kValidModel, "wall: 0.01}", "wall: 0.01, colour: red}"));
  EXPECT_EQ(e.line(), 5);
  EXPECT_EQ(e.key(), "colour");
}

TEST(ModelReader, MissingKeyNamesLineAndKey) {
  const auto e = model_error_of(replace_first(kValidModel, "  steel: {E: 2.1e11, nu: 0.3, rho: 7850}", "  steel: {E: 2.1e11, nu: 0.3}"));
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.key(), "rho");
}

TEST(ModelReader, WrongTypeNamesLineAndKey) {
  const auto e = model_error_of(replace_first(kValidModel, "elements: 3", "elements: three"));
  EXPECT_EQ(e.line(), 11);
  EXPECT_EQ(e.key(), "elements");
}

TEST(ModelReader, NonPositiveModulus) {
  const auto e = model_error_of(replace_first(kValidModel, "E: 2.1e11", "E: -2.1e11"));
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.key(), "E");
}

TEST(ModelReader, NonPositiveDensity) {
  const auto e = model_error_of(replace_first(kValidModel, "rho: 7850", "rho: 0"));
  EXPECT_EQ(e.key(), "rho");
}

TEST(ModelReader, NonPositiveSectionDimension) {
  const auto e = model_error_of(replace_first(kValidModel, "wall: 0.01", "wall: 0"));
  EXPECT_EQ(e.line(), 5);
  EXPECT_EQ(e.key(), "wall");
}

TEST(ModelReader, DuplicateNodeId) {
  const auto e = model_error_of(replace_first(kValidModel, "  - [2, 0, 0, 2]", "  - [1, 0, 0, 2]"));
  EXPECT_EQ(e.line(), 9);
  EXPECT_NE(std::string(e.what()).find("duplicate node id 1"), std::string::npos);
}

TEST(ModelReader, ElementNamingAMissingNode) {
  const auto e = model_error_of(replace_first(kValidModel, "nodes: [1, 2], section: col", "nodes: [1, 9], section: col"));
  EXPECT_EQ(e.line(), 17);
  EXPECT_NE(std::string(e.what()).find("node 9"), std::string::npos);
}

TEST(ModelReader, ZeroLengthElement) {
  const auto e = model_error_of(replace_first(kValidModel, "nodes: [1, 2], section: col", "nodes: [1, 1], section: col"));
  EXPECT_EQ(e.line(), 17);
  EXPECT_NE(std::string(e.what()).find("zero length"), std::string::npos);
}

TEST(ModelReader, UnknownSection) {
  const auto e = model_error_of(replace_first(kValidModel, "nodes: [1, 2], section: col", "nodes: [1, 2], section: pipe"));
  EXPECT_EQ(e.line(), 17);
  EXPECT_EQ(e.key(), "section");
}

TEST(ModelReader, CouplingWhoseNodesCoincide) {
  std::string text = kValidModel;
  text += "couplings:\n  - {id: c, reference: 2, nodes: [3]}\n";
  text = replace_first(text, "  - [2, 0, 0, 2]", "  - [2, 0, 0, 2]\n  - [3, 0, 0, 2.0]");
  const auto e = model_error_of(text);
  EXPECT_EQ(e.key(), "nodes");
  EXPECT_NE(std::string(e.what()).find("coincides"), std::string::npos);
}

TEST(ModelReader, PositionThatMatchesNoNode) {
  const auto e = model_error_of(replace_first(kValidModel, "at: [3, 0, 2]", "at: [3, 0, 2.5]"));
  EXPECT_EQ(e.line(), 15);
  EXPECT_EQ(e.key(), "at");
}

TEST(ModelReader, DegenerateShell) {
  const std::string text = R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
shell_sections:
  plate: {material: steel, thickness: 0.01}
nodes:
  - [1, 0, 0, 0]
  - [2, 1, 0, 0]
  - [3, 2, 0, 0]
  - [4, 3, 0, 0]
shells:
  - {id: flat, nodes: [1, 2, 3, 4], section: plate}
)";
  const auto e = model_error_of(text);
  EXPECT_EQ(e.line(), 11);
}

const char* kSolidModel = R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
nodes:
  - [101, 0, 0, 2]
  - [102, 1, 0, 2]
  - [103, 1, 1, 2]
  - [104, 0, 1, 2]
  - [105, 0, 0, 3]
  - [106, 1, 0, 3]
  - [107, 1, 1, 3]
  - [108, 0, 1, 3]
solids:
  - {id: cap, nodes: [101, 102, 103, 104, 105, 106, 107, 108], material: steel}
solid_blocks:
  - {id: base, corners: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 2], [1, 0, 2], [1, 1, 2], [0, 1, 2]],
     divisions: [2, 2, 4], element: hex20, material: steel, mass: lumped}
)";

TEST(ModelReader, ReadsSolidsAndSolidBlocks) {
  const io::ModelFile f = io::parse_model(kSolidModel, "solid.yaml");
  ASSERT_EQ(f.model.solids.size(), 1u + 2 * 2 * 4);
  EXPECT_EQ(f.model.solids[0].id, "cap");
  EXPECT_EQ(f.model.solids[1].nodes.size(), 20u);
  EXPECT_EQ(f.model.solids[1].mass, fe::MassKind::Lumped);
  // The block's top corners merge with the cap's lower nodes 101-104: the
  // hex20 grid of 2 x 2 x 4 cells has 5 x 5 x 9 = 225 points, 84 of them with
  // two or three odd indices (face and cell centres, no node), so 141 nodes,
  // plus the cap's four upper ones.
  EXPECT_EQ(f.model.nodes.size(), 141u + 4u);
  auto in_block = [&](fe::NodeId id) {
    return std::any_of(f.model.solids.begin() + 1, f.model.solids.end(), [&](const fe::SolidElement& s) {
      return std::find(s.nodes.begin(), s.nodes.end(), id) != s.nodes.end();
    });
  };
  for (fe::NodeId id : {101, 102, 103, 104}) EXPECT_TRUE(in_block(id)) << id;
  for (fe::NodeId id : {105, 106, 107, 108}) EXPECT_FALSE(in_block(id)) << id;
}

TEST(ModelReader, SolidErrorsNameLineAndKey) {
  {
    const auto e = model_error_of(replace_first(kSolidModel, "element: hex20", "element: hex27"));
    EXPECT_EQ(e.line(), 16);
    EXPECT_EQ(e.key(), "element");
    EXPECT_NE(std::string(e.what()).find("hex8, hex20 or tet10"), std::string::npos) << e.what();
  }
  {
    const auto e = model_error_of(replace_first(kSolidModel, "107, 108]", "107]"));
    EXPECT_EQ(e.line(), 13);
    EXPECT_EQ(e.key(), "nodes");
  }
  {  // corners 1-4 clockwise seen from 5's side: an inverted element
    const auto e = model_error_of(replace_first(kSolidModel, "[101, 102, 103, 104,", "[101, 104, 103, 102,"));
    EXPECT_EQ(e.line(), 13);
    EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos) << e.what();
  }
  {
    const auto e =
        model_error_of(replace_first(kSolidModel, "material: steel}\nsolid_blocks", "material: iron}\nsolid_blocks"));
    EXPECT_EQ(e.line(), 13);
    EXPECT_EQ(e.key(), "material");
  }
}

TEST(ModelReader, DistributingCouplingIsReadAndItsErrorsNamed) {
  const std::string text = std::string(kSolidModel) + R"(couplings:
  - {id: hub, kind: distributing, reference: 900, nodes: [105, 106, 107, 108], weights: [1, 2, 1, 2]}
)";
  const std::string with_node = replace_first(text, "nodes:\n", "nodes:\n  - [900, 0.5, 0.5, 3.5]\n");
  const io::ModelFile f = io::parse_model(with_node, "solid.yaml");
  ASSERT_EQ(f.model.distributing_couplings.size(), 1u);
  EXPECT_EQ(f.model.distributing_couplings[0].weights, (std::vector<double>{1, 2, 1, 2}));
  EXPECT_TRUE(f.model.couplings.empty());
  {
    const auto e = model_error_of(replace_first(with_node, "weights: [1, 2, 1, 2]", "dofs: [UX]"));
    EXPECT_EQ(e.key(), "dofs");
  }
  {
    const auto e = model_error_of(replace_first(with_node, "weights: [1, 2, 1, 2]", "weights: [1, 2]"));
    EXPECT_EQ(e.line(), 19);
    EXPECT_EQ(e.key(), "weights");
  }
  {
    const auto e =
        model_error_of(replace_first(with_node, "[105, 106, 107, 108], weights: [1, 2, 1, 2]", "[105, 106]"));
    EXPECT_EQ(e.line(), 19);
    EXPECT_NE(std::string(e.what()).find("one line"), std::string::npos) << e.what();
  }
  {
    const auto e = model_error_of(replace_first(with_node, "kind: distributing", "kind: glued"));
    EXPECT_EQ(e.key(), "kind");
  }
}

TEST(ModelReader, NonPositiveThickness) {
  const auto e = model_error_of("materials:\n  s: {E: 1e9, nu: 0.3, rho: 1000}\nshell_sections:\n  p: {material: s, thickness: -1}\nnodes:\n  - [1, 0, 0, 0]\n");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.key(), "thickness");
}

TEST(ModelReader, MissingFile) {
  EXPECT_THROW(io::read_model("/nonexistent/model.yaml"), io::InputError);
}

}  // namespace
}  // namespace rigflex
