#pragma once
// The shell element types, one entry each, with everything the rest of
// rigflex needs to know about a type: the reader and the model's checks
// (node counts), the element loop (its matrices), the VTK writer (its cell)
// and the CalculiX cross-check (the ccx element it is compared with). A new
// shell formulation is an entry here plus its matrices function and tests
// (docs/extending.md).
#include <string>
#include <vector>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"
#include "fe/shell_element.hpp"

namespace rigflex::fe {

struct ShellType {
  const char* name = "";      // in messages and docs
  const char* order = "";     // the mesher's `order:` value that generates it
  int nodes = 0;              // corners counter-clockwise, then mid-sides 1-2, 2-3, 3-4, 4-1
  int vtk_cell = 0;           // VTK cell type (vtkCellType.h); fe itself does not use VTK
  const char* calculix = "";  // the ccx element the cross-checks compare it with
  ElementMatrices (*matrices)(const std::vector<Vec3>& x, const ShellProperties& p) = nullptr;
  // Coordinates of the element's own, carried by the first DOFs of a node
  // generated for it (ShellElement::centre, add_shell_centres()), and the
  // matrices on the nodes' DOFs then those; 0 and nullptr if it has none.
  int own_coordinates = 0;
  ElementMatrices (*matrices_with_own)(const std::vector<Vec3>& x, const ShellProperties& p) = nullptr;
};

// Every shell type, in a fixed order (the CalculiX deck groups by it).
const std::vector<ShellType>& shell_types();

// The type with this many nodes; nullptr if there is none. An element's type
// is chosen by its node count.
const ShellType* shell_type_with_nodes(size_t nodes);

// The type of a validated element; throws std::invalid_argument if none has
// its node count.
const ShellType& shell_type(const ShellElement& s);

// The node counts for messages: "4 or 8".
std::string shell_node_counts();

}  // namespace rigflex::fe
