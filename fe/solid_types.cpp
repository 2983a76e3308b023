#include "fe/solid_types.hpp"

#include <stdexcept>

namespace rigflex::fe {

const std::vector<SolidType>& solid_types() {
  // vtk_cell: VTK_HEXAHEDRON = 12, VTK_QUADRATIC_HEXAHEDRON = 25 and
  // VTK_QUADRATIC_TETRA = 24 take rigflex's node orders; C3D8I is ccx's
  // incompatible-mode brick, the same formulation as hex8.
  static const std::vector<SolidType> types = {
      {"hex8", 8, 12, "C3D8I", solid_hex8},
      {"hex20", 20, 25, "C3D20", solid_hex20},
      {"tet10", 10, 24, "C3D10", solid_tet10},
  };
  return types;
}

const SolidType* solid_type_with_nodes(size_t nodes) {
  for (const SolidType& t : solid_types())
    if (static_cast<size_t>(t.nodes) == nodes) return &t;
  return nullptr;
}

const SolidType* solid_type_named(const std::string& name) {
  for (const SolidType& t : solid_types())
    if (name == t.name) return &t;
  return nullptr;
}

const SolidType& solid_type(const SolidElement& s) {
  const SolidType* t = solid_type_with_nodes(s.nodes.size());
  if (!t)
    throw std::invalid_argument("solid '" + s.id + "': no solid type has " + std::to_string(s.nodes.size()) + " nodes");
  return *t;
}

namespace {
template <class F>
std::string listed(F f) {
  std::string s;
  const auto& types = solid_types();
  for (size_t i = 0; i < types.size(); ++i) s += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + f(types[i]);
  return s;
}
}  // namespace

std::string solid_node_counts() {
  return listed([](const SolidType& t) { return std::to_string(t.nodes); });
}
std::string solid_type_names() {
  return listed([](const SolidType& t) { return std::string(t.name); });
}

}  // namespace rigflex::fe
