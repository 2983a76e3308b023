#include "io/rig_vtk.hpp"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <cstdio>

#include "io/vtk_mesh.hpp"
#include "io/vtk_modes.hpp"

namespace rigflex::io {
namespace {

// Points: A_1..A_n, B_1..B_n, P, CoG. The displacement of each under an
// increment s of the coordinates is the "velocity" of the point when the
// coordinate rates are s (the kinematics are linear in the rates).
std::vector<Eigen::Vector3d> skeleton(const rig::Kinematics& k) {
  std::vector<Eigen::Vector3d> p;
  for (const auto& r : k.rods) p.push_back(r.A);
  for (const auto& r : k.rods) p.push_back(r.B);
  p.push_back(k.r);
  p.push_back(k.cog);
  return p;
}

std::vector<Eigen::Vector3d> skeleton_motion(const rig::Kinematics& dk) {
  std::vector<Eigen::Vector3d> d;
  for (const auto& r : dk.rods) d.push_back(r.vA);
  for (const auto& r : dk.rods) d.push_back(r.vB);
  d.push_back(dk.v);
  d.push_back(dk.v + dk.omega.cross(dk.cog - dk.r));
  return d;
}

rig::Velocity as_rates(const rig::RigSystem& rig, const Eigen::VectorXd& s) {
  rig::Velocity v = rig.at_rest();
  v.V = s.segment<3>(0);
  v.w = s.segment<3>(3);
  if (rig.elastic_modes()) v.eta = s.segment(6, rig.elastic_modes());
  if (rig.fixed_dofs()) v.xf = s.segment(6 + rig.elastic_modes(), rig.fixed_dofs());
  return v;
}

void write_grid(const std::filesystem::path& file, const std::vector<Eigen::Vector3d>& points,
                const std::vector<Eigen::Vector3d>& motion, int n, const rig::RigMode& mode, int index, double scale) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& p : points) pts->InsertNextPoint(p.x(), p.y(), p.z());
  grid->SetPoints(pts);
  vtkNew<vtkIntArray> part;  // 1 fixed frame, 2 rod, 3 carrying frame + body
  part->SetName("component");
  auto line = [&](vtkIdType a, vtkIdType b, int c) {
    const vtkIdType ids[2] = {a, b};
    grid->InsertNextCell(VTK_LINE, 2, ids);
    part->InsertNextValue(c);
  };
  const vtkIdType P = 2 * n, G = 2 * n + 1;
  for (int i = 0; i < n; ++i) {
    line(i, (i + 1) % n, 1);
    line(i, n + i, 2);
    line(n + i, n + (i + 1) % n, 3);
    line(P, n + i, 3);
  }
  line(P, G, 3);
  grid->GetCellData()->AddArray(part);
  vtkNew<vtkDoubleArray> u;
  u->SetName("translation");
  u->SetNumberOfComponents(3);
  for (const auto& d : motion) u->InsertNextTuple3(d.x(), d.y(), d.z());
  grid->GetPointData()->AddArray(u);
  grid->GetPointData()->SetActiveVectors("translation");
  vtkNew<vtkDoubleArray> f;
  f->SetName("frequency_hz");
  f->InsertNextValue(mode.frequency_hz);
  vtkNew<vtkIntArray> m;
  m->SetName("mode");
  m->InsertNextValue(index);
  vtkNew<vtkStringArray> kind;
  kind->SetName("kind");
  kind->InsertNextValue(rig::to_string(mode.kind));
  grid->GetFieldData()->AddArray(f);
  grid->GetFieldData()->AddArray(m);
  grid->GetFieldData()->AddArray(kind);
  vtkNew<vtkDoubleArray> shown;
  shown->SetName("display_scale");
  shown->InsertNextValue(scale);
  grid->GetFieldData()->AddArray(shown);
  write_vtu(grid, file, VtuEncoding::ascii);
}

}  // namespace

void add_rig_mode_files(FileBatch& batch, const std::filesystem::path& dir, const rig::RigSystem& rig,
                        const rig::Linearization& lin) {
  const rig::Configuration& c = lin.equilibrium.configuration;
  const auto points = skeleton(rig.kinematics(c, rig.at_rest(), 0.0));
  // Scale each shape so that its largest skeleton displacement is
  // kDisplayShare of the mean rod length: ParaView's warp then shows every
  // mode at a readable size; the factor is kept in `display_scale`.
  double L = 0;
  for (const auto& r : rig.assembly().geometry.rods) L += r.length / rig.rods();
  std::vector<std::string> names;
  Eigen::VectorXd f(static_cast<Eigen::Index>(lin.modes.size()));
  for (size_t k = 0; k < lin.modes.size(); ++k) {
    const rig::RigMode& mode = lin.modes[k];
    auto motion = skeleton_motion(rig.kinematics(c, as_rates(rig, mode.shape), 0.0));
    double largest = 0;
    for (const auto& d : motion) largest = std::max(largest, d.norm());
    const double scale = largest > 0 ? kDisplayShare * L / largest : 1.0;
    for (auto& d : motion) d *= scale;
    char name[48];
    std::snprintf(name, sizeof name, "rig_mode_%03zu.vtu", k + 1);
    names.emplace_back(name);
    f(static_cast<Eigen::Index>(k)) = mode.frequency_hz;
    const int n = rig.rods(), index = static_cast<int>(k + 1);
    batch.add(dir / name, [points, motion, n, mode, index, scale](const std::filesystem::path& tmp) {
      write_grid(tmp, points, motion, n, mode, index, scale);
    });
  }
  batch.add_text(dir / "rig_modes.pvd", mode_collection(f, names));
}

}  // namespace rigflex::io
