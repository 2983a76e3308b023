// The rig assembly for ParaView (io/rig_assembly_vtk.hpp): the large example
// rig's FE fixed frame, rods, rigid carrying frame and body box where the
// equilibrium puts them, read back with VTK's own reader; the equivalent
// box against its closed form.
#include <gtest/gtest.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <map>
#include <vector>

#include "io/rig_assembly_vtk.hpp"
#include "io/rig_reader.hpp"
#include "rig/equilibrium.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

namespace fs = std::filesystem;

// A box of sides (a, b, c) along rotated axes has J = m/12 Q diag(b^2 + c^2,
// a^2 + c^2, a^2 + b^2) Q': the equivalent box gives the sides back, and its
// inertia is the body's.
TEST(RigAssemblyVtk, EquivalentBoxHasTheBodysInertia) {
  fe::MassProperties body;
  body.mass = 120.0;
  body.cog = Eigen::Vector3d(0.1, -0.2, 0.3);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d s(1.5, 0.6, 0.9);
  const Eigen::Vector3d d(s(1) * s(1) + s(2) * s(2), s(0) * s(0) + s(2) * s(2), s(0) * s(0) + s(1) * s(1));
  body.inertia = body.mass / 12 * Q * d.asDiagonal() * Q.transpose();
  const io::EquivalentBox box = io::equivalent_box(body);
  std::vector<double> sides{box.sides(0), box.sides(1), box.sides(2)};
  std::sort(sides.begin(), sides.end());
  EXPECT_NEAR(sides[0], 0.6, 1e-12);
  EXPECT_NEAR(sides[1], 0.9, 1e-12);
  EXPECT_NEAR(sides[2], 1.5, 1e-12);
  EXPECT_NEAR(box.axes.determinant(), 1.0, 1e-12);
  const Eigen::Vector3d& b = box.sides;
  const Eigen::Vector3d db(b(1) * b(1) + b(2) * b(2), b(0) * b(0) + b(2) * b(2), b(0) * b(0) + b(1) * b(1));
  const Eigen::Matrix3d J = body.mass / 12 * box.axes * db.asDiagonal() * box.axes.transpose();
  EXPECT_LE((J - body.inertia).cwiseAbs().maxCoeff(), 1e-12 * body.inertia.norm());
  body.mass = 0;
  EXPECT_THROW(io::equivalent_box(body), std::invalid_argument);
}

TEST(RigAssemblyVtk, LargeRigFramesRodsAndBodyWhereTheEquilibriumPutsThem) {
  const fs::path file = fs::path(RIGFLEX_SOURCE_DIR) / "examples/large-rig/rig.yaml";
  const rig::RigSpec spec = io::read_rig_spec(file);
  const rig::RigModel model = io::resolve_rig(spec, {});
  const rig::RigSystem system(model);
  const rig::Equilibrium eq = rig::static_equilibrium(system);
  ASSERT_TRUE(eq.converged) << eq.message;
  const io::AssemblyFrames frames = io::assembly_frames(spec);
  ASSERT_TRUE(frames.fixed.has_value());
  ASSERT_NE(frames.fixed->mesh, nullptr);
  EXPECT_FALSE(frames.carrying.has_value());  // rigid: drawn through its joints

  test::TempDir dir("rigflex-assembly");
  io::FileBatch batch;
  io::add_rig_assembly_file(batch, dir.path() / "rig_assembly.vtu", system, eq.configuration, frames);
  batch.commit();
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir.path() / "rig_assembly.vtu").string().c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  vtkDataArray* component = grid->GetCellData()->GetArray("component");
  vtkDataArray* kind = grid->GetCellData()->GetArray("element_kind");
  ASSERT_NE(component, nullptr);
  ASSERT_NE(kind, nullptr);
  std::map<int, int> cells;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) ++cells[static_cast<int>(component->GetTuple1(c))];
  const fe::Model& mesh = *frames.fixed->mesh;
  size_t elements = mesh.beams.size() + mesh.shells.size() + mesh.solids.size() + mesh.point_masses.size();
  for (const auto& c : mesh.couplings) elements += c.dependents.size();  // a line to each node tied
  for (const auto& c : mesh.distributing_couplings) elements += c.nodes.size();
  ASSERT_FALSE(mesh.couplings.empty());                           // the joints hang from the beams by rigid couplings
  EXPECT_EQ(cells[io::kFixedFrame], static_cast<int>(elements));  // the whole mesh
  EXPECT_EQ(cells[io::kRods], 3);
  EXPECT_EQ(cells[io::kCarryingFrame], 3 + 3);  // the joints' triangle and P to each joint
  EXPECT_EQ(cells[io::kBody], 1);

  const rig::Kinematics k = system.kinematics(eq.configuration, system.at_rest(), 0.0);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    vtkCell* cell = grid->GetCell(c);
    const int part = static_cast<int>(component->GetTuple1(c));
    if (part == io::kRods) {
      // Each rod from its upper to its lower joint centre at equilibrium.
      double a[3], bpt[3];
      grid->GetPoint(cell->GetPointId(0), a);
      grid->GetPoint(cell->GetPointId(1), bpt);
      bool found = false;
      for (const auto& r : k.rods)
        found |= (Eigen::Vector3d(a[0], a[1], a[2]) - r.A).norm() < 1e-12 &&
                 (Eigen::Vector3d(bpt[0], bpt[1], bpt[2]) - r.B).norm() < 1e-12;
      EXPECT_TRUE(found) << "rod cell " << c;
    }
    if (part == io::kBody) {
      // The box's corners average at the CoG in G.
      ASSERT_EQ(cell->GetNumberOfPoints(), 8);
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (vtkIdType p = 0; p < 8; ++p) {
        double x[3];
        grid->GetPoint(cell->GetPointId(p), x);
        centre += Eigen::Vector3d(x[0], x[1], x[2]) / 8;
      }
      EXPECT_LE((centre - k.cog).norm(), 1e-9);
      EXPECT_EQ(kind->GetTuple1(c), io::kBodyBoxCell);
    }
  }
  // The FE frame, drawn as built, sits on the joints as built: each nominal
  // upper joint centre has a mesh node within the rig file's matching
  // tolerance (1 cm); the rods hang from the loaded joints, the frame's
  // static deflection below them, which the file states.
  double deflection = 0;
  for (size_t i = 0; i < k.rods.size(); ++i)
    deflection = std::max(deflection, (k.rods[i].A - model.geometry.rods[i].upper).norm());
  EXPECT_GT(deflection, 0.01);  // the large rig's soft frame: centimetres
  vtkDataArray* stated = grid->GetFieldData()->GetArray("fixed_frame_joint_deflection");
  ASSERT_NE(stated, nullptr);
  EXPECT_NEAR(stated->GetTuple1(0), deflection, 1e-12);
  ASSERT_NE(grid->GetFieldData()->GetArray("carrying_frame_joint_deflection"), nullptr);
  EXPECT_EQ(grid->GetFieldData()->GetArray("carrying_frame_joint_deflection")->GetTuple1(0), 0.0);  // rigid
  for (const auto& rod : model.geometry.rods) {
    const Eigen::Vector3d joint = rod.upper;
    double nearest = 1e9;
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
      if (static_cast<int>(component->GetTuple1(c)) != io::kFixedFrame) continue;
      vtkCell* cell = grid->GetCell(c);
      for (vtkIdType p = 0; p < cell->GetNumberOfPoints(); ++p) {
        double x[3];
        grid->GetPoint(cell->GetPointId(p), x);
        nearest = std::min(nearest, (Eigen::Vector3d(x[0], x[1], x[2]) - joint).norm());
      }
    }
    EXPECT_LE(nearest, 0.01);
  }
  vtkDataArray* mass = grid->GetFieldData()->GetArray("body_mass");
  ASSERT_NE(mass, nullptr);
  EXPECT_EQ(mass->GetTuple1(0), system.assembly().body.mass);
  ASSERT_NE(grid->GetFieldData()->GetArray("box_sides"), nullptr);
}

}  // namespace
}  // namespace rigflex
