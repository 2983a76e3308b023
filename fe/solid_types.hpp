#pragma once
// The solid element types, one entry each (as fe/shell_types.hpp for shells):
// node count, the mesher's name, the VTK cell, the CalculiX element the
// cross-checks compare it with, and its matrices function.
#include <string>
#include <vector>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"
#include "fe/solid_element.hpp"

namespace rigflex::fe {

struct SolidType {
  const char* name = "";      // in messages, docs and `element:` of solid_blocks
  int nodes = 0;              // node order: fe/solid_element.hpp
  int vtk_cell = 0;           // VTK cell type (vtkCellType.h); fe itself does not use VTK
  const char* calculix = "";  // the ccx element the cross-checks compare it with
  ElementMatrices (*matrices)(const std::vector<Vec3>& x, const SolidProperties& p) = nullptr;
};

const std::vector<SolidType>& solid_types();
// nullptr if no type has this many nodes / this name.
const SolidType* solid_type_with_nodes(size_t nodes);
const SolidType* solid_type_named(const std::string& name);
// The type of a validated element; throws std::invalid_argument if none has its node count.
const SolidType& solid_type(const SolidElement& s);
// "8, 20 or 10" and "hex8, hex20 or tet10", for messages.
std::string solid_node_counts();
std::string solid_type_names();

}  // namespace rigflex::fe
