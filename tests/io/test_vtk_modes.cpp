// Mode-shape files (io/vtk_modes.hpp) read back with VTK's own reader: each
// shell and solid type's cell arrives with the type's node count, and each
// edge of a quadratic solid cell has its middle point halfway between its
// ends, so ParaView draws the element the model has.
#include <gtest/gtest.h>
#include <vtkCell.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "fe/meshers.hpp"
#include "fe/shell_types.hpp"
#include "fe/solid_types.hpp"
#include "io/vtk_modes.hpp"

namespace rigflex::io {
namespace {

// Writes a mode-shape file of m and reads it back with VTK's reader.
vtkSmartPointer<vtkUnstructuredGrid> written_grid(const fe::Model& m, const std::string& name) {
  const fe::AssembledSystem sys = fe::assemble(m);
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  FileBatch batch;
  add_mode_shape_files(batch, dir, m, sys.dofs, Eigen::VectorXd::Ones(1),
                       Eigen::MatrixXd::Zero(sys.dofs.free_count(), 1));
  batch.commit();
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir / "mode_001.vtu").string().c_str());
  reader->Update();
  return reader->GetOutput();
}

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
  vtkSmartPointer<vtkUnstructuredGrid> grid = written_grid(m, "vtk_shell_types");
  ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(fe::shell_types().size()));
  for (size_t i = 0; i < fe::shell_types().size(); ++i) {
    const fe::ShellType& t = fe::shell_types()[i];
    SCOPED_TRACE(t.name);
    EXPECT_EQ(grid->GetCellType(static_cast<vtkIdType>(i)), t.vtk_cell);
    EXPECT_EQ(grid->GetCell(static_cast<vtkIdType>(i))->GetNumberOfPoints(), t.nodes);
  }
}

TEST(VtkModes, EachSolidTypesCellHasTheTypesNodesInVtkOrder) {
  for (const fe::SolidType& t : fe::solid_types()) {
    SCOPED_TRACE(t.name);
    fe::Model m;
    m.materials["steel"] = fe::Material{"steel", 210e9, 0.3, 7850.0};
    fe::NodeMerger merger(m);
    fe::SolidBlockSpec spec;
    spec.id = "b";
    spec.corners = {fe::Vec3(0, 0, 0),     fe::Vec3(2, 0.1, 0),   fe::Vec3(2.2, 1.3, 0.1), fe::Vec3(-0.1, 1, 0),
                    fe::Vec3(0.1, 0, 0.9), fe::Vec3(2.1, 0, 1.2), fe::Vec3(2, 1.1, 1),     fe::Vec3(0, 1.2, 1.1)};
    spec.element = t.name;
    spec.material = "steel";
    fe::mesh_solid_block(m, merger, spec);
    vtkSmartPointer<vtkUnstructuredGrid> grid = written_grid(m, std::string("vtk_solid_") + t.name);
    ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(m.solids.size()));
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
      EXPECT_EQ(grid->GetCellType(c), t.vtk_cell);
      vtkCell* cell = grid->GetCell(c);
      ASSERT_EQ(cell->GetNumberOfPoints(), t.nodes);
      if (t.nodes == 8) continue;
      // VTK's own edge table of the cell: ends, then the middle point.
      for (int e = 0; e < cell->GetNumberOfEdges(); ++e) {
        vtkCell* edge = cell->GetEdge(e);
        ASSERT_EQ(edge->GetNumberOfPoints(), 3);
        double a[3], b[3], mid[3];
        edge->GetPoints()->GetPoint(0, a);
        edge->GetPoints()->GetPoint(1, b);
        edge->GetPoints()->GetPoint(2, mid);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], 0.5 * (a[k] + b[k]), 1e-12) << "edge " << e;
      }
    }
  }
}

// Mode shapes are written scaled for display: `translation` is the shape
// times the field `display_scale`, its largest motion 5 % of the model's
// largest extent; a shape that does not move keeps scale 1.
TEST(VtkModes, ShapesAreScaledForDisplayWithTheFactorKept) {
  fe::Model m;
  m.materials["steel"] = fe::Material{"steel", 210e9, 0.3, 7850.0};
  fe::NodeMerger merger(m);
  fe::SolidBlockSpec spec;
  spec.id = "b";
  spec.corners = {fe::Vec3(0, 0, 0), fe::Vec3(4, 0, 0), fe::Vec3(4, 1, 0), fe::Vec3(0, 1, 0),
                  fe::Vec3(0, 0, 1), fe::Vec3(4, 0, 1), fe::Vec3(4, 1, 1), fe::Vec3(0, 1, 1)};
  spec.nx = 4;
  spec.element = "hex8";
  spec.material = "steel";
  fe::mesh_solid_block(m, merger, spec);
  const fe::AssembledSystem sys = fe::assemble(m);
  Eigen::VectorXd shape(sys.dofs.free_count());
  for (Eigen::Index i = 0; i < shape.size(); ++i) shape(i) = 1e-3 * std::sin(0.7 * static_cast<double>(i) + 0.3);
  Eigen::MatrixXd shapes(shape.size(), 2);
  shapes << shape, Eigen::VectorXd::Zero(shape.size());
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "vtk_display_scale";
  std::filesystem::remove_all(dir);
  FileBatch batch;
  add_mode_shape_files(batch, dir, m, sys.dofs, Eigen::Vector2d(1.0, 2.0), shapes);
  batch.commit();
  const Eigen::VectorXd full = sys.dofs.expand(shape);
  for (int k : {1, 2}) {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir / (k == 1 ? "mode_001.vtu" : "mode_002.vtu")).string().c_str());
    reader->Update();
    vtkUnstructuredGrid* grid = reader->GetOutput();
    vtkDataArray* scale_array = grid->GetFieldData()->GetArray("display_scale");
    ASSERT_NE(scale_array, nullptr);
    const double scale = scale_array->GetTuple1(0);
    vtkDataArray* u = grid->GetPointData()->GetArray("translation");
    ASSERT_NE(u, nullptr);
    ASSERT_EQ(u->GetNumberOfTuples(), static_cast<vtkIdType>(m.nodes.size()));
    if (k == 2) {
      EXPECT_EQ(scale, 1.0);
      continue;
    }
    double largest = 0;
    for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i) {
      const double* t = u->GetTuple3(i);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], scale * full(6 * i + c), 1e-15 * scale);
      largest = std::max(largest, std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]));
    }
    EXPECT_NEAR(largest, kDisplayShare * 4.0, 1e-12);  // the block's largest extent is 4 m
  }
}

// A rotation counts as the motion it makes at the model's far end.
TEST(VtkModes, DisplayScaleWeighsRotationsByTheExtent) {
  Eigen::VectorXd shape = Eigen::VectorXd::Zero(12);
  shape(3) = 0.1;   // node 1 RX
  shape(6) = 0.05;  // node 2 UX
  EXPECT_NEAR(display_scale(shape, 2.0), kDisplayShare * 2.0 / 0.2, 1e-15);
  EXPECT_NEAR(display_scale(shape, 0.1), kDisplayShare * 0.1 / 0.05, 1e-15);
  EXPECT_EQ(display_scale(Eigen::VectorXd::Zero(12), 2.0), 1.0);
}

}  // namespace
}  // namespace rigflex::io
