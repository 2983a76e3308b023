#include "fe/shell_types.hpp"

#include <stdexcept>

namespace rigflex::fe {

const std::vector<ShellType>& shell_types() {
  // vtk_cell: VTK_QUAD = 9 and VTK_QUADRATIC_QUAD = 23, whose node orders are
  // rigflex's; S4 and S8R are the elements ccx's results are compared with
  // (docs/fe-core.md).
  static const std::vector<ShellType> types = {
      {"MITC4", "linear", 4, 9, "S4", shell_mitc4},
      {"Quad8", "quadratic", 8, 23, "S8R", shell_quad8, 3, shell_quad8_with_centre},
  };
  return types;
}

const ShellType* shell_type_with_nodes(size_t nodes) {
  for (const ShellType& t : shell_types())
    if (static_cast<size_t>(t.nodes) == nodes) return &t;
  return nullptr;
}

const ShellType& shell_type(const ShellElement& s) {
  const ShellType* t = shell_type_with_nodes(s.nodes.size());
  if (!t) throw std::invalid_argument("shell '" + s.id + "': no shell type has " + std::to_string(s.nodes.size()) + " nodes");
  return *t;
}

std::string shell_node_counts() {
  std::string s;
  const auto& types = shell_types();
  for (size_t i = 0; i < types.size(); ++i) {
    s += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + std::to_string(types[i].nodes);
  }
  return s;
}

}  // namespace rigflex::fe
