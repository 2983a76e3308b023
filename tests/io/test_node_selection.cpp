// Nodes chosen by where they are (fe/node_selection.hpp) in a model file:
// node sets, supports and couplings take `box`, `line`, `plane` and `near`
// beside ids and set names. The model: a 2 x 1 m shell patch, 4 x 2 MITC4,
// so its 15 nodes lie on a 0.5 m grid, and a 1 m column above its corner.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "io/input_error.hpp"
#include "io/model_reader.hpp"
#include "support/input_errors.hpp"

namespace rigflex {
namespace {

const std::string kModel = R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
beam_sections:
  col: {material: steel, shape: box, width: 0.2, height: 0.2, wall: 0.01}
shell_sections:
  plate: {material: steel, thickness: 0.01}
shell_patches:
  - {id: p, corners: [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], divisions: [4, 2], order: linear, section: plate}
members:
  - {id: c, from: [2, 1, 0], to: [2, 1, 1], elements: 2, section: col}
)";

fe::Model with(const std::string& extra) { return io::parse_model(kModel + extra, "model.yaml").model; }

std::vector<fe::Vec3> positions(const fe::Model& m, const std::string& set) {
  std::vector<fe::Vec3> x;
  for (fe::NodeId id : m.node_set(set)) x.push_back(m.position(id));
  return x;
}

TEST(NodeSelection, LinePlaneNearAndBoxPickTheNodesThere) {
  const fe::Model m = with(R"(node_sets:
  edge: {line: [[0, 0, 0], [2, 0, 0]]}
  half_edge: {line: [[0, 0, 0], [1, 0, 0]]}
  diagonal: {line: [[0, 0, 0], [2, 1, 0]]}
  plate: {plane: [[0, 0, 0], [0, 0, 3]]}
  end: {plane: [[2, 5, 5], [1, 0, 0]]}
  around: {near: [[1, 0.5, 0], 0.5]}
  column: {box: [[1.9, 0.9, 0.1], [2.1, 1.1, 2]]}
)");
  auto ys = [](const std::vector<fe::Vec3>& x) {
    return std::all_of(x.begin(), x.end(), [](const fe::Vec3& p) { return p.y() == 0 && p.z() == 0; });
  };
  EXPECT_EQ(positions(m, "edge").size(), 5u);
  EXPECT_TRUE(ys(positions(m, "edge")));
  EXPECT_EQ(positions(m, "half_edge").size(), 3u);  // 0, 0.5 and 1 m: the segment, not the line
  EXPECT_EQ(positions(m, "diagonal").size(), 3u);   // (0,0), (1,0.5), (2,1): the grid points on it
  EXPECT_EQ(positions(m, "plate").size(), 15u);     // every patch node, none of the column above
  EXPECT_EQ(positions(m, "end").size(), 5u);        // x = 2: three plate nodes and the column's two above
  EXPECT_EQ(positions(m, "around").size(), 5u);     // the centre and its four neighbours at 0.5 m
  EXPECT_EQ(positions(m, "column").size(), 2u);
}

TEST(NodeSelection, SupportsAndCouplingsTakeThemToo) {
  const fe::Model m = with(R"(supports:
  - {id: clamp, line: [[0, 0, 0], [0, 1, 0]], dofs: all}
couplings:
  - {id: rbe, kind: distributing, reference_at: [2, 1, 1], near: [[2, 0.5, 0], 0.5]}
)");
  EXPECT_EQ(m.supports.size(), 3u);
  ASSERT_EQ(m.distributing_couplings.size(), 1u);
  EXPECT_EQ(m.distributing_couplings.front().nodes.size(), 4u);  // (2,0), (2,0.5), (2,1), (1.5,0.5)
}

TEST(NodeSelection, BadSelectionsNameLineAndKey) {
  struct Case {
    std::string text, key, fragment;
  };
  const Case cases[] = {
      {"node_sets:\n  s: {line: [[0, 0, 0], [0, 0, 0]]}\n", "line", "ends coincide"},
      {"node_sets:\n  s: {line: [[0, 0, 0]]}\n", "line", "ends of a segment"},
      {"node_sets:\n  s: {plane: [[0, 0, 0], [0, 0, 0]]}\n", "plane", "normal is zero"},
      {"node_sets:\n  s: {near: [[0, 0, 0], -1]}\n", "near", "zero or positive"},
      {"node_sets:\n  s: {line: [[0, 0, 5], [1, 0, 5]]}\n", "line", "no node selected"},
      {"node_sets:\n  s: {near: [[0, 0, 0], 0.1], box: [[0, 0, 0], [1, 1, 1]]}\n", "nodes", "exactly one of"},
  };
  for (const Case& c : cases) {
    const io::InputError e = test::input_error_of([&] { with(c.text); }, c.text);
    EXPECT_EQ(e.file(), "model.yaml") << c.text;
    EXPECT_EQ(e.line(), 12) << c.text;
    EXPECT_EQ(e.key(), c.key) << c.text;
    EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rigflex
