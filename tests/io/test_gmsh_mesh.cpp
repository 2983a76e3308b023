// Gmsh meshes in a model file (io/gmsh_mesh.hpp), on meshes Gmsh 4.8.4 wrote
// (tests/io/gmsh/README.md), ASCII and binary: the same plate and bar
// meshed by rigflex's own meshers give the same modes (to round-off: Gmsh's
// node coordinates differ in the last digits), so node order, element
// types and groups are read right; a free 10-node tetrahedral mesh of the
// bar lands within 1.5 % of the 20-node hexahedra (measured 0.6 %: a
// different mesh); faults name the file and line.
#include <gtest/gtest.h>

#include <string>

#include "io/gmsh_mesh.hpp"
#include "io/input_error.hpp"
#include "io/model_reader.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/input_errors.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

const std::string kDir = std::string(RIGFLEX_SOURCE_DIR) + "/tests/io/gmsh/";

Eigen::VectorXd modes(const std::string& model_text) {
  const io::ModelFile f = io::parse_model(model_text, kDir + "model.yaml");
  linalg::EigenOptions o;
  o.count = 6;
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(f.model, o);
  EXPECT_TRUE(a.result.converged) << a.result.message;
  return a.result.frequencies_hz();
}

const std::string kSteel = "materials:\n  steel: {E: 2.1e11, nu: 0.3, rho: 7850}\n";

std::string plate_from(const std::string& msh) {
  return kSteel + "shell_sections:\n  plate: {material: steel, thickness: 0.012}\nmeshes:\n  - {id: m, file: " + msh +
         ", shells: {plate: plate}}\nsupports:\n  - {set: root, dofs: all}\n";
}

std::string bar_from(const std::string& msh) {
  return kSteel + "meshes:\n  - {id: m, file: " + msh +
         ", solids: {bar: steel}}\nsupports:\n  - {set: root, dofs: translations}\n";
}

void expect_same(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double tol, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (Eigen::Index k = 0; k < a.size(); ++k) EXPECT_NEAR(a(k) / b(k), 1.0, tol) << what << " mode " << k + 1;
}

TEST(GmshMesh, APlateGivesTheModesOfTheSameMeshFromTheMesher) {
  const Eigen::VectorXd own = modes(kSteel + R"(shell_sections:
  plate: {material: steel, thickness: 0.012}
shell_patches:
  - {id: p, corners: [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], divisions: [4, 2], order: quadratic, section: plate}
supports:
  - {line: [[0, 0, 0], [0, 1, 0]], dofs: all}
)");
  for (const char* msh : {"plate.msh", "plate_bin.msh"}) expect_same(modes(plate_from(msh)), own, 1e-9, msh);
  const io::ModelFile f = io::parse_model(plate_from("plate.msh"), kDir + "model.yaml");
  EXPECT_EQ(f.model.shells.size(), 8u);
  EXPECT_EQ(f.model.node_set("root").size(), 5u);    // the edge's corner and mid-side nodes
  EXPECT_EQ(f.model.node_set("plate").size(), 37u);  // every node of the 8-node grid
}

TEST(GmshMesh, ABarGivesTheModesOfTheSameMeshFromTheMesherAndTetrahedraComeClose) {
  const Eigen::VectorXd own = modes(kSteel + R"(solid_blocks:
  - {id: b, corners: [[0, 0, 0], [1, 0, 0], [1, 0.4, 0], [0, 0.4, 0], [0, 0, 0.2], [1, 0, 0.2], [1, 0.4, 0.2], [0, 0.4, 0.2]],
     divisions: [6, 2, 2], element: hex20, material: steel}
supports:
  - {plane: [[0, 0, 0], [1, 0, 0]], dofs: translations}
)");
  for (const char* msh : {"block.msh", "block_bin.msh"}) expect_same(modes(bar_from(msh)), own, 1e-9, msh);
  expect_same(modes(bar_from("tet.msh")), own, 1.5e-2, "tet.msh");
}

// A triangle placed as a shell, for the messages below.
const std::string kTriangle = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "skin"
$EndPhysicalNames
$Entities
0 0 1 0
1 0 0 0 1 1 0 1 1 0
$EndEntities
$Nodes
1 3 1 3
2 1 0 3
1
2
3
0 0 0
1 0 0
0 1 0
$EndNodes
$Elements
1 1 1 1
2 1 2 1
1 1 2 3
$EndElements
)";

TEST(GmshMesh, FaultsNameTheFileAndLine) {
  test::TempDir dir("gmsh");
  const std::string model = kSteel +
                            "shell_sections:\n  plate: {material: steel, thickness: 0.01}\n"
                            "meshes:\n  - {id: m, file: mesh.msh, shells: {skin: plate}}\n";
  struct Case {
    std::string msh;
    int line;
    std::string fragment;
  };
  auto replace = [](std::string s, const std::string& a, const std::string& b) {
    return s.replace(s.find(a), a.size(), b);
  };
  const Case cases[] = {
      {kTriangle, 25, "3-node triangle: rigflex's shells are 4- and 8-node quadrangles"},
      {replace(kTriangle, "4.1 0 8", "2.2 0 8"), 2, "MSH version 2.2"},
      {replace(kTriangle, "1 1 2 3\n", "1 1 2 7\n"), 25, "names node 7"},
      {replace(kTriangle, "1 0 0\n", "1 zero 0\n"), 19, "'zero' is not a number"},
      {kTriangle.substr(0, kTriangle.find("$EndNodes")), 20, "the file ends"},  // its last line
  };
  for (const Case& c : cases) {
    test::write_text(dir.path() / "mesh.msh", c.msh);
    const io::InputError e =
        test::input_error_of([&] { io::parse_model(model, (dir.path() / "model.yaml").string()); }, c.msh);
    EXPECT_EQ(e.file(), (dir.path() / "mesh.msh").string()) << c.fragment;
    EXPECT_EQ(e.line(), c.line) << c.fragment << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
  }
  // A group the mesh does not have is named at the model file's key.
  test::write_text(dir.path() / "mesh.msh", kTriangle);
  const std::string wrong = replace(model, "{skin: plate}", "{hull: plate}");
  const io::InputError e =
      test::input_error_of([&] { io::parse_model(wrong, (dir.path() / "model.yaml").string()); }, wrong);
  EXPECT_EQ(e.file(), (dir.path() / "model.yaml").string());
  EXPECT_EQ(e.line(), 6);
  EXPECT_EQ(e.key(), "shells");
  EXPECT_NE(std::string(e.what()).find("no surface physical group 'hull'"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace rigflex
