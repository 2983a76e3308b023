// Abaqus / CalculiX decks read as models (io/abaqus_deck.hpp).
//  - The table frame of tests/io/abaqus (S8R plate, B32R legs, a block on a
//    rigid body, a spring, clamped feet; split over *INCLUDE files) gives
//    the modes of the same frame written as a rigflex YAML model and as a
//    Gmsh mesh of its plate, to round-off: the three readers build the
//    same model (element types, node order, sections, set semantics).
//  - Each keyword's meaning on small decks (sets with GENERATE, sections
//    and their 1-direction, masses and rotary inertia, springs, boundary
//    types, rigid bodies, couplings on node and element surfaces).
//  - Every fault names the file (the included one where it lies), the line
//    and the keyword.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fe/beam_element.hpp"
#include "io/abaqus_deck.hpp"
#include "io/input_error.hpp"
#include "io/model_reader.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/input_errors.hpp"
#include "support/temp_files.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

const std::string kDeckDir = std::string(RIGFLEX_SOURCE_DIR) + "/tests/io/";

Eigen::VectorXd deck_modes(const fe::Model& model) {
  return test::checked_modal_analysis(model, 10).result.frequencies_hz();
}

// The table frame's parts as a rigflex model; `plate` places the plate.
std::string table_yaml(const std::string& plate) {
  return R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
beam_sections:
  leg: {material: steel, shape: tube, diameter: 0.1, wall: 0.005}
shell_sections:
  plate: {material: steel, thickness: 0.012}
)" + plate +
         R"(
members:
  - {id: l1, from: [0, 0, -1], to: [0, 0, 0], elements: 2, section: leg}
  - {id: l2, from: [2, 0, -1], to: [2, 0, 0], elements: 2, section: leg}
  - {id: l3, from: [2, 1, -1], to: [2, 1, 0], elements: 2, section: leg}
  - {id: l4, from: [0, 1, -1], to: [0, 1, 0], elements: 2, section: leg}
nodes:
  - [900, 1, 0.5, 0.3]
point_masses:
  - {id: block, node: 900, mass: 200}
couplings:
  - {id: hanger, reference: 900, near: [[1, 0.5, 0], 0.26]}
springs:
  - {id: k, at: [1, 0, 0], stiffness: [0, 0, 1e6, 0, 0, 0]}
supports:
  - {plane: [[0, 0, -1], [0, 0, 1]], dofs: all}
)";
}

TEST(AbaqusDeck, TheTableFrameGivesTheModesOfItsYamlModelAndOfItsGmshMesh) {
  const io::ModelFile deck = io::read_model(kDeckDir + "abaqus/frame.inp");
  EXPECT_EQ(deck.name, "table frame");
  EXPECT_EQ(deck.model.shells.size(), 8u);
  EXPECT_EQ(deck.model.beams.size(), 8u);  // each B32R split at its middle node
  EXPECT_EQ(deck.model.node_set("CENTRE").size(), 5u);
  EXPECT_EQ(deck.model.node_set("FEET").size(), 4u);
  const Eigen::VectorXd from_deck = deck_modes(deck.model);

  const io::ModelFile yaml = io::parse_model(
      table_yaml(
          "shell_patches:\n  - {id: p, corners: [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], divisions: [4, 2], "
          "section: plate}"),
      kDeckDir + "abaqus/frame.yaml");
  const io::ModelFile gmsh =
      io::parse_model(table_yaml("meshes:\n  - {id: m, file: ../gmsh/plate.msh, shells: {plate: plate}}"),
                      kDeckDir + "abaqus/frame.yaml");
  const Eigen::VectorXd from_yaml = deck_modes(yaml.model), from_gmsh = deck_modes(gmsh.model);
  ASSERT_EQ(from_deck.size(), 10);
  for (Eigen::Index k = 0; k < 10; ++k) {
    // Gmsh writes coordinates with round-off in the last digits.
    EXPECT_NEAR(from_deck(k) / from_yaml(k), 1.0, 1e-9) << "mode " << k + 1;
    EXPECT_NEAR(from_gmsh(k) / from_yaml(k), 1.0, 1e-9) << "mode " << k + 1;
  }
}

io::ModelFile deck(const std::string& text) { return io::parse_abaqus_deck(text, "deck.inp"); }

const std::string kDeckSteel = "*MATERIAL, NAME=steel\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850.\n";

TEST(AbaqusDeck, SetsGenerateAndNameOtherSetsCaseInsensitively) {
  std::string text = "*NODE, NSET=all\n";
  for (int i = 1; i <= 9; ++i) text += std::to_string(i) + ", " + std::to_string(0.5 * (i - 1)) + ", 0, 0\n";
  text += "*ELEMENT, TYPE=B31, ELSET=bars\n1, 1, 2\n2, 2, 3\n3, 3, 4\n4, 4, 5\n5, 5, 6\n6, 6, 7\n7, 7, 8\n8, 8, 9\n" +
          kDeckSteel +
          "*nset, nset=odd, generate\n1, 9, 2\n*NSET, NSET=ends\n1, 9\n*NSET, NSET=Both\nODD, ends, 4\n"
          "*ELSET, ELSET=half, GENERATE\n1, 4\n*NSET, NSET=halfnodes, ELSET=HALF\n"
          "*BEAM SECTION, ELSET=BARS, MATERIAL=STEEL, SECTION=RECT\n0.02, 0.04\n0., 0., -1.\n"
          "*BOUNDARY\nends, 1, 6\n";
  const io::ModelFile f = deck(text);
  EXPECT_EQ(f.model.node_set("odd"), (std::vector<fe::NodeId>{1, 3, 5, 7, 9}));
  EXPECT_EQ(f.model.node_set("Both"), (std::vector<fe::NodeId>{1, 3, 5, 7, 9, 4}));  // distinct, in order
  EXPECT_EQ(f.model.node_set("halfnodes"), (std::vector<fe::NodeId>{1, 2, 3, 4, 5}));
  EXPECT_EQ(f.model.supports.size(), 2u);
  EXPECT_EQ(f.name, "deck");  // no *HEADING: the file's stem
}

// One 1 m beam along x with the given section card lines.
io::ModelFile one_beam(const std::string& section) {
  return deck("*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*ELEMENT, TYPE=B31, ELSET=B\n1, 1, 2\n" + kDeckSteel + section);
}

TEST(AbaqusDeck, BeamSectionsTakeTheirDimensionsAndTheOneDirection) {
  // RECT a (along n1 = rigflex's local y) x b; n1 = +Y makes local z = t x n1 = +Z.
  io::ModelFile f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n0.02, 0.05\n0, 1, 0\n");
  const fe::BeamSection& rect = f.model.beam_sections.at("B");
  EXPECT_EQ(rect.shape, fe::SectionShape::Rectangle);
  EXPECT_DOUBLE_EQ(rect.width, 0.02);
  EXPECT_DOUBLE_EQ(rect.height, 0.05);
  const fe::BeamElement& b = f.model.beams.front();
  const Eigen::Matrix3d R = fe::beam_local_axes(f.model.position(1), f.model.position(2), b.orientation);
  EXPECT_NEAR((R.row(1).transpose() - fe::Vec3::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((R.row(2).transpose() - fe::Vec3::UnitZ()).norm(), 0.0, 1e-12);
  // Without the line Abaqus's default n1 = (0, 0, -1): local z = x cross -z = +y.
  f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n0.02, 0.05\n");
  const Eigen::Matrix3d D = fe::beam_local_axes(f.model.position(1), f.model.position(2), f.model.beams[0].orientation);
  EXPECT_NEAR((D.row(2).transpose() - fe::Vec3::UnitY()).norm(), 0.0, 1e-12);

  // CIRC: one value is Abaqus's radius, two are CalculiX's diameters.
  f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=CIRC\n0.025\n0, 1, 0\n");
  EXPECT_DOUBLE_EQ(f.model.beam_sections.at("B").diameter, 0.05);
  f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=CIRC\n0.05, 0.05\n0, 1, 0\n");
  EXPECT_DOUBLE_EQ(f.model.beam_sections.at("B").diameter, 0.05);
  f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=PIPE\n0.05, 0.004\n0, 1, 0\n");
  EXPECT_DOUBLE_EQ(f.model.beam_sections.at("B").diameter, 0.1);
  EXPECT_DOUBLE_EQ(f.model.beam_sections.at("B").wall, 0.004);
  f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=BOX\n0.1, 0.2, 0.004, 0.006, 0.004, 0.006\n0,1,0\n");
  const fe::BeamSection& box = f.model.beam_sections.at("B");
  EXPECT_DOUBLE_EQ(box.web_thickness, 0.004);  // t1, t3: the walls at +-n1
  EXPECT_DOUBLE_EQ(box.flange_thickness, 0.006);
  f = one_beam("*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=I\n0.15, 0.3, 0.2, 0.2, 0.014, 0.014, 0.0085\n0,1,0\n");
  const fe::BeamSection& i = f.model.beam_sections.at("B");
  EXPECT_EQ(i.shape, fe::SectionShape::ISection);
  EXPECT_DOUBLE_EQ(i.height, 0.3);
  EXPECT_DOUBLE_EQ(i.web_thickness, 0.0085);

  // A general section: its own E and G (nu from them), DENSITY=, shear areas K / G.
  f = deck(
      "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*ELEMENT, TYPE=B31, ELSET=B\n1, 1, 2\n"
      "*BEAM GENERAL SECTION, ELSET=B, SECTION=GENERAL, DENSITY=7800\n1e-3, 2e-6, 0, 3e-6, 1e-6\n0, 1, 0\n"
      "2e11, 8e10\n*TRANSVERSE SHEAR STIFFNESS\n4e7, 6e7\n");
  const fe::BeamSection& g = f.model.beam_sections.at("B");
  const fe::Material& gm = f.model.materials.at(g.material);
  EXPECT_DOUBLE_EQ(g.Iy, 2e-6);
  EXPECT_DOUBLE_EQ(g.Iz, 3e-6);
  EXPECT_DOUBLE_EQ(gm.nu, 0.25);
  EXPECT_DOUBLE_EQ(gm.rho, 7800.0);
  EXPECT_DOUBLE_EQ(*g.shear_area_z, 4e7 / 8e10);
  EXPECT_DOUBLE_EQ(*g.shear_area_y, 6e7 / 8e10);
}

TEST(AbaqusDeck, MassesSpringsBoundariesAndB32) {
  const io::ModelFile f = deck(
      "*HEADING\nsmall, one\n*NODE\n1, 0, 0, 0\n2, 0.5, 0, 0\n3, 1, 0, 0\n4, 2, 0, 0\n"
      "*ELEMENT, TYPE=B32, ELSET=B\n1, 1, 2, 3\n*ELEMENT, TYPE=MASS, ELSET=M\n10, 3\n"
      "*ELEMENT, TYPE=ROTARYI, ELSET=J\n11, 3\n*ELEMENT, TYPE=SPRING1, ELSET=K1\n12, 1\n"
      "*ELEMENT, TYPE=SPRING2, ELSET=K2\n13, 3, 4\n*ELEMENT, TYPE=SPRINGA, ELSET=KA\n14, 3, 4\n" +
      kDeckSteel +
      "*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n0.02, 0.04\n0, 1, 0\n"
      "*MASS, ELSET=M\n12.5\n*ROTARY INERTIA, ELSET=J\n1, 2, 3, -0.1, -0.2\n"
      "*SPRING, ELSET=K1\n5\n1e4\n*SPRING, ELSET=K2\n2, 2\n3e5\n*SPRING, ELSET=KA\n\n7e6\n"
      "*BOUNDARY\n1, ENCASTRE\n4, 1, 3\n4, XSYMM\n*STEP\n*FREQUENCY\n5\n*BOUNDARY\n4, 6\n*END STEP\n");
  EXPECT_EQ(f.name, "small, one");
  ASSERT_EQ(f.model.beams.size(), 2u);
  EXPECT_EQ(f.model.beams[0].nodes, (std::array<fe::NodeId, 2>{1, 2}));
  EXPECT_EQ(f.model.beams[1].nodes, (std::array<fe::NodeId, 2>{2, 3}));
  ASSERT_EQ(f.model.point_masses.size(), 1u);  // MASS and ROTARYI on one node: one point mass
  EXPECT_DOUBLE_EQ(f.model.point_masses[0].mass, 12.5);
  EXPECT_EQ(f.model.point_masses[0].inertia, (std::array<double, 6>{1, 2, 3, -0.1, -0.2, 0}));
  ASSERT_EQ(f.model.springs.size(), 3u);
  EXPECT_DOUBLE_EQ(f.model.springs[0].stiffness[4], 1e4);
  EXPECT_FALSE(f.model.springs[0].other);
  EXPECT_DOUBLE_EQ(f.model.springs[1].stiffness[1], 3e5);
  EXPECT_EQ(*f.model.springs[1].other, 4);
  EXPECT_DOUBLE_EQ(*f.model.springs[2].axial, 7e6);
  ASSERT_EQ(f.model.supports.size(), 2u);
  EXPECT_EQ(f.model.supports[0].fixed, (fe::DofMask{true, true, true, true, true, true}));
  // 1-3, XSYMM (1, 5, 6) and the step's 6.
  EXPECT_EQ(f.model.supports[1].fixed, (fe::DofMask{true, true, true, false, true, true}));
}

TEST(AbaqusDeck, RigidBodiesAndCouplingsOnNodeAndElementSurfaces) {
  std::string text = "*NODE\n";
  const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i)
    text += std::to_string(i + 1) + ", " + std::to_string(c[i][0]) + ", " + std::to_string(c[i][1]) + ", " +
            std::to_string(c[i][2]) + "\n";
  text +=
      "100, 0.5, 0.5, 2\n101, 0.5, 0.5, -1\n102, 2, 0.5, 0.5\n*ELEMENT, TYPE=C3D8I, ELSET=BLOCK\n1, 1, 2, 3, 4, 5, 6, "
      "7, 8\n" +
      kDeckSteel +
      "*SOLID SECTION, ELSET=BLOCK, MATERIAL=steel\n*ELEMENT, TYPE=MASS, ELSET=M\n2, 100\n3, 101\n4, 102\n"
      "*MASS, ELSET=M\n5\n*SURFACE, NAME=top, TYPE=ELEMENT\nBLOCK, S2\n"
      "*SURFACE, NAME=side, TYPE=NODE\n2, 2.\n3\n4\n"
      "*COUPLING, REF NODE=100, SURFACE=top, CONSTRAINT NAME=lid\n*KINEMATIC\n1, 3\n"
      "*COUPLING, REF NODE=102, SURFACE=side, CONSTRAINT NAME=hub\n*DISTRIBUTING\n"
      "*NSET, NSET=bottom\n1\n*RIGID BODY, NSET=bottom, REF NODE=101\n"
      "*BOUNDARY\n101, ENCASTRE\n";
  const io::ModelFile f = deck(text);
  ASSERT_EQ(f.model.couplings.size(), 2u);
  const fe::RigidCoupling& lid = f.model.couplings[0];
  EXPECT_EQ(lid.id, "lid");
  EXPECT_EQ(lid.dependents, (std::vector<fe::NodeId>{5, 8, 7, 6}));  // face S2: 5-8-7-6
  EXPECT_EQ(lid.dofs, (fe::DofMask{true, true, true, false, false, false}));
  EXPECT_EQ(f.model.couplings[1].dependents, (std::vector<fe::NodeId>{1}));
  EXPECT_EQ(f.model.couplings[1].dofs, (fe::DofMask{true, true, true, true, true, true}));
  ASSERT_EQ(f.model.distributing_couplings.size(), 1u);
  EXPECT_EQ(f.model.distributing_couplings[0].nodes, (std::vector<fe::NodeId>{2, 3, 4}));
  EXPECT_EQ(f.model.distributing_couplings[0].weights, (std::vector<double>{2, 1, 1}));
}

TEST(AbaqusDeck, FaultsNameTheFileLineAndKeyword) {
  test::TempDir dir("abaqus");
  const std::string nodes = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n";
  const std::string beam = "*ELEMENT, TYPE=B31, ELSET=B\n1, 1, 2\n";
  const std::string section = "*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n0.02, 0.04\n0, 1, 0\n";
  struct Case {
    std::string text;
    int line;
    std::string key, fragment;
  };
  const Case cases[] = {
      {nodes + beam + kDeckSteel + section + "*CLOAD\n2, 3, 100.\n", 14, "*CLOAD", "loads are not part"},
      {nodes + "*ELEMENT, TYPE=S3\n1, 1, 2, 1\n", 4, "TYPE", "no triangular shell element"},
      {nodes + "*ELEMENT, TYPE=B31\n1, 1, 7\n", 5, "*ELEMENT", "names node 7"},
      {nodes + beam + kDeckSteel, 5, "*ELEMENT", "has no section"},
      {nodes + "2, 3, 0, 0\n", 4, "*NODE", "node 2 is defined twice"},
      {nodes + beam + section, 6, "MATERIAL", "material 'steel' is not defined"},
      {nodes + beam + kDeckSteel + section + "*BOUNDARY\n1, 1, 3, 0.01\n", 15, "*BOUNDARY", "nonzero prescribed"},
      {nodes + beam + kDeckSteel + section + "*STEP\n*STATIC\n", 15, "*STATIC", "make the step a *FREQUENCY step"},
      {"*PART, NAME=p\n" + nodes, 1, "*PART", "parts and instances"},
      {nodes + beam + kDeckSteel + "*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT, OFFSET1=0.1\n0.1, 0.1\n", 11,
       "*BEAM SECTION", "parameter OFFSET1 is not supported"},
      {nodes + beam + kDeckSteel + "*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n0.1, 0.1\n1, 0, 0\n", 5,
       "*ELEMENT", "lies along its section's 1-direction"},
      {nodes + beam + kDeckSteel + "*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n0.1, wide\n", 12,
       "*BEAM SECTION", "'wide' is not a finite number"},
      {nodes + beam + kDeckSteel + "*BEAM SECTION, ELSET=B, MATERIAL=steel, SECTION=RECT\n-0.1, 0.1\n", 11, "width",
       "width must be positive"},
      {"1, 0, 0, 0\n", 1, "", "a data line before the first keyword"},
      {nodes + "*INCLUDE, INPUT=missing.inp\n", 4, "*INCLUDE", "missing.inp' is not a file"},
  };
  for (const Case& c : cases) {
    test::write_text(dir.path() / "deck.inp", c.text);
    const io::InputError e = test::input_error_of([&] { io::read_model(dir.path() / "deck.inp"); }, c.text);
    EXPECT_EQ(e.file(), (dir.path() / "deck.inp").string()) << c.fragment;
    EXPECT_EQ(e.line(), c.line) << c.fragment << ": " << e.what();
    EXPECT_EQ(e.key(), c.key) << c.fragment << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
  }
  // A fault in an included file names that file and its line.
  test::write_text(dir.path() / "mesh.inp", nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 1, 2\n");
  test::write_text(dir.path() / "deck.inp", "** the model\n*INCLUDE, INPUT=mesh.inp\n");
  const io::InputError e = test::input_error_of([&] { io::read_model(dir.path() / "deck.inp"); }, "include");
  EXPECT_EQ(e.file(), (dir.path() / "mesh.inp").string());
  EXPECT_EQ(e.line(), 4);
  EXPECT_NE(std::string(e.what()).find("C3D10"), std::string::npos) << e.what();
  // An include cycle stops.
  test::write_text(dir.path() / "deck.inp", "*INCLUDE, INPUT=deck.inp\n");
  const io::InputError cycle = test::input_error_of([&] { io::read_model(dir.path() / "deck.inp"); }, "cycle");
  EXPECT_NE(std::string(cycle.what()).find("nested deeper"), std::string::npos) << cycle.what();
}

}  // namespace
}  // namespace rigflex
