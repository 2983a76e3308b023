#pragma once
// A finite element model's elements as VTK cells, shared by the mode shapes
// (io/vtk_modes.hpp) and the rig assembly (io/rig_assembly_vtk.hpp).
#include <vtkIntArray.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Core>
#include <filesystem>
#include <functional>

#include "fe/model.hpp"

namespace rigflex::io {

// Cell kinds in the array `element_kind`: ParaView thresholds by them.
enum ElementKind : int { kBeamCell = 1, kShellCell = 2, kPointMassCell = 3, kSolidCell = 4 };

// Appends `model`'s nodes (through `place`) as points of `grid` and its
// beams, shells, solids and point masses as cells, one `kind` value per cell.
// `grid` must already hold a vtkPoints. Returns the cells added.
vtkIdType append_mesh(vtkUnstructuredGrid& grid, vtkIntArray& kind, const fe::Model& model,
                      const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& place);

// How a .vtu holds its arrays: readable text, or one raw appended block.
enum class VtuEncoding { ascii, appended };

// Writes `grid` as a VTK XML unstructured grid; std::runtime_error naming
// `file` when VTK cannot.
void write_vtu(vtkUnstructuredGrid* grid, const std::filesystem::path& file, VtuEncoding encoding);

}  // namespace rigflex::io
