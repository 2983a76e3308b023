#pragma once
// The nodes that carry element coordinates rather than displacements.
#include <vector>

#include "fe/model.hpp"

namespace rigflex::fe {

// Gives every shell whose type has coordinates of its own (the 8-node
// shell's centre) and whose mass is consistent a node of its own for them,
// placed at the element's centre and numbered after every existing node, so
// that the element keeps its centre's dynamics instead of condensing it
// statically (fe/shell_element.hpp). Readers call it last, so no selector of
// an input file ever takes such a node. Elements that have one keep it.
void add_shell_centres(Model& model);

// Nodes whose DOFs are coordinates, not displacements: superelements' modal
// nodes and shells' centres. Rigid motions leave them at zero, and they are
// no place in space a mode shape could be drawn at.
std::vector<NodeId> coordinate_nodes(const Model& model);

}  // namespace rigflex::fe
