#include "io/vtk_mesh.hpp"

#include <vtkCellType.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <stdexcept>
#include <vector>

#include "fe/shell_types.hpp"
#include "fe/solid_types.hpp"

namespace rigflex::io {

vtkIdType append_mesh(vtkUnstructuredGrid& grid, vtkIntArray& kind, const fe::Model& model,
                      const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& place) {
  vtkPoints* points = grid.GetPoints();
  const vtkIdType first = points->GetNumberOfPoints();
  for (const fe::Node& n : model.nodes) {
    const Eigen::Vector3d x = place(n.x);
    points->InsertNextPoint(x.x(), x.y(), x.z());
  }
  auto idx = [&](fe::NodeId id) { return first + static_cast<vtkIdType>(model.node_index(id)); };
  const vtkIdType cells = grid.GetNumberOfCells();
  for (const fe::BeamElement& b : model.beams) {
    const vtkIdType ids[2] = {idx(b.nodes[0]), idx(b.nodes[1])};
    grid.InsertNextCell(VTK_LINE, 2, ids);
    kind.InsertNextValue(kBeamCell);
  }
  for (const fe::ShellElement& s : model.shells) {
    std::vector<vtkIdType> ids;
    for (fe::NodeId id : s.nodes) ids.push_back(idx(id));
    // The type's VTK cell takes our node order (tests/io check its point count).
    grid.InsertNextCell(fe::shell_type(s).vtk_cell, static_cast<vtkIdType>(ids.size()), ids.data());
    kind.InsertNextValue(kShellCell);
  }
  for (const fe::SolidElement& s : model.solids) {
    std::vector<vtkIdType> ids;
    for (fe::NodeId id : s.nodes) ids.push_back(idx(id));
    grid.InsertNextCell(fe::solid_type(s).vtk_cell, static_cast<vtkIdType>(ids.size()), ids.data());
    kind.InsertNextValue(kSolidCell);
  }
  for (const fe::PointMass& p : model.point_masses) {
    const vtkIdType id = idx(p.node);
    grid.InsertNextCell(VTK_VERTEX, 1, &id);
    kind.InsertNextValue(kPointMassCell);
  }
  return grid.GetNumberOfCells() - cells;
}

void write_vtu(vtkUnstructuredGrid* grid, const std::filesystem::path& file, VtuEncoding encoding) {
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(file.string().c_str());
  writer->SetInputData(grid);
  if (encoding == VtuEncoding::ascii) {
    writer->SetDataModeToAscii();
  } else {
    writer->SetDataModeToAppended();
  }
  if (writer->Write() != 1) throw std::runtime_error("VTK could not write " + file.string());
}

}  // namespace rigflex::io
