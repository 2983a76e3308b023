// The shell type table (fe/shell_types.hpp): every entry is complete and
// usable, and an element's type follows its node count.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "fe/shell_types.hpp"
#include "test_shell_helpers.hpp"

namespace rigflex::fe {
namespace {

// A flat unit square with the type's nodes; a type with another node count
// needs its geometry here before its entry can pass.
std::vector<Vec3> flat_element(int nodes) {
  const std::vector<Vec3> corners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  if (nodes == 4) return corners;
  if (nodes == 8) return shell_test::with_midsides(corners);
  ADD_FAILURE() << "no test geometry for a " << nodes << "-node shell";
  return {};
}

TEST(ShellTypes, EveryEntryIsCompleteAndItsMatricesHaveItsNodeCount) {
  std::set<int> node_counts;
  std::set<std::string> names, orders;
  for (const ShellType& t : shell_types()) {
    SCOPED_TRACE(t.name);
    EXPECT_TRUE(node_counts.insert(t.nodes).second) << "node counts choose the type, so they must differ";
    EXPECT_TRUE(names.insert(t.name).second);
    EXPECT_TRUE(orders.insert(t.order).second);
    EXPECT_GT(t.vtk_cell, 0);
    EXPECT_STRNE(t.calculix, "");
    ASSERT_NE(t.matrices, nullptr);
    const ElementMatrices e = t.matrices(flat_element(t.nodes), {200e9, 0.3, 7850.0, 0.01, MassKind::Consistent});
    EXPECT_EQ(e.K.rows(), 6 * t.nodes);
    EXPECT_EQ(e.M.rows(), 6 * t.nodes);
    // Symmetrized explicitly by the elements, so exact.
    EXPECT_EQ((e.K - e.K.transpose()).norm(), 0.0);
    // Coordinates of its own: both or neither, and then the matrices have them last.
    EXPECT_EQ(t.own_coordinates > 0, t.matrices_with_own != nullptr);
    if (!t.matrices_with_own) continue;
    const ElementMatrices own =
        t.matrices_with_own(flat_element(t.nodes), {200e9, 0.3, 7850.0, 0.01, MassKind::Consistent});
    EXPECT_EQ(own.K.rows(), 6 * t.nodes + t.own_coordinates);
    EXPECT_EQ(own.M.rows(), 6 * t.nodes + t.own_coordinates);
    EXPECT_EQ((own.K - own.K.transpose()).norm(), 0.0);
  }
}

TEST(ShellTypes, AnElementsTypeFollowsItsNodeCount) {
  ShellElement s;
  s.id = "s1";
  for (const ShellType& t : shell_types()) {
    s.nodes.assign(static_cast<size_t>(t.nodes), 1);
    EXPECT_EQ(&shell_type(s), &t);
    EXPECT_EQ(shell_type_with_nodes(s.nodes.size()), &t);
  }
  s.nodes.assign(5, 1);
  EXPECT_EQ(shell_type_with_nodes(5), nullptr);
  EXPECT_THROW(shell_type(s), std::invalid_argument);
  EXPECT_EQ(shell_node_counts(), "4 or 8");
}

}  // namespace
}  // namespace rigflex::fe
