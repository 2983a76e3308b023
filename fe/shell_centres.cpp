#include "fe/shell_centres.hpp"

#include "fe/shell_types.hpp"

namespace rigflex::fe {

void add_shell_centres(Model& model) {
  NodeId next = 0;
  for (ShellElement& s : model.shells) {
    const ShellType* type = shell_type_with_nodes(s.nodes.size());
    if (s.centre != 0 || !type || type->own_coordinates == 0 || s.mass != MassKind::Consistent) continue;
    if (next == 0) next = model.next_node_id();
    // The 8-node map's image of (0, 0): mid-sides' mean twice, less the corners'.
    Vec3 x = Vec3::Zero();
    for (size_t i = 0; i < s.nodes.size(); ++i) x += (i < 4 ? -0.25 : 0.5) * model.position(s.nodes[i]);
    s.centre = model.add_node(next++, x);
  }
}

std::vector<NodeId> coordinate_nodes(const Model& model) {
  std::vector<NodeId> ids;
  for (const Superelement& e : model.superelements) ids.insert(ids.end(), e.modal_nodes.begin(), e.modal_nodes.end());
  for (const ShellElement& s : model.shells)
    if (s.centre != 0) ids.push_back(s.centre);
  return ids;
}

}  // namespace rigflex::fe
