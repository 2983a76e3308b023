// Mode-shape files (io/vtk_modes.hpp) read back with VTK's own reader: each
// shell type's cell arrives with the type's node count, so ParaView draws
// the element the model has.
#include <gtest/gtest.h>
#include <vtkCell.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>

#include "fe/shell_types.hpp"
#include "io/vtk_modes.hpp"

namespace rigflex::io {
namespace {

TEST(VtkModes, EachShellTypesCellHasTheTypesNodes) {
  fe::Model m;
  m.materials["steel"] = fe::Material{"steel", 210e9, 0.3, 7850.0};
  m.shell_sections["plate"] = fe::ShellSection{"plate", "steel", 0.01};
  fe::NodeId next = 1;
  double x0 = 0.0;
  for (const fe::ShellType& t : fe::shell_types()) {
    // Unit square corners, then mid-sides where the type has them.
    std::vector<fe::Vec3> corners = {{x0, 0, 0}, {x0 + 1, 0, 0}, {x0 + 1, 1, 0}, {x0, 1, 0}};
    std::vector<fe::Vec3> x = corners;
    for (size_t i = 0; x.size() < static_cast<size_t>(t.nodes) && i < 4; ++i)
      x.push_back(0.5 * (corners[i] + corners[(i + 1) % 4]));
    ASSERT_EQ(x.size(), static_cast<size_t>(t.nodes)) << "no test geometry for " << t.name;
    fe::ShellElement s;
    s.id = t.name;
    s.section = "plate";
    for (const fe::Vec3& p : x) s.nodes.push_back(m.add_node(next++, p));
    m.shells.push_back(s);
    x0 += 2.0;
  }
  const fe::AssembledSystem sys = fe::assemble(m);
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "vtk_shell_types";
  std::filesystem::remove_all(dir);
  FileBatch batch;
  add_mode_shape_files(batch, dir, m, sys.dofs, Eigen::VectorXd::Ones(1),
                       Eigen::MatrixXd::Zero(sys.dofs.free_count(), 1));
  batch.commit();

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir / "mode_001.vtu").string().c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(fe::shell_types().size()));
  for (size_t i = 0; i < fe::shell_types().size(); ++i) {
    const fe::ShellType& t = fe::shell_types()[i];
    SCOPED_TRACE(t.name);
    EXPECT_EQ(grid->GetCellType(static_cast<vtkIdType>(i)), t.vtk_cell);
    EXPECT_EQ(grid->GetCell(static_cast<vtkIdType>(i))->GetNumberOfPoints(), t.nodes);
  }
}

}  // namespace
}  // namespace rigflex::io
