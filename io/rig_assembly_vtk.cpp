#include "io/rig_assembly_vtk.hpp"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <utility>

#include "io/vtk_mesh.hpp"

namespace rigflex::io {
namespace {

using Vec3 = Eigen::Vector3d;

// The grid being built: points, cells and their two cell arrays in step.
class AssemblyGrid {
 public:
  AssemblyGrid() {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    grid_->SetPoints(points);
    component_->SetName("component");
    kind_->SetName("element_kind");
  }

  vtkIdType point(const Vec3& x) { return grid_->GetPoints()->InsertNextPoint(x.x(), x.y(), x.z()); }

  void cell(int vtk_type, const std::vector<vtkIdType>& ids, int component, int kind) {
    grid_->InsertNextCell(vtk_type, static_cast<vtkIdType>(ids.size()), ids.data());
    component_->InsertNextValue(component);
    kind_->InsertNextValue(kind);
  }

  // A closed polygon through `corners` as lines (two corners: one line).
  void outline(const std::vector<Vec3>& corners, int component) {
    std::vector<vtkIdType> ids;
    for (const Vec3& x : corners) ids.push_back(point(x));
    const size_t n = ids.size();
    for (size_t i = 0; i + 1 < n + (n > 2 ? 1 : 0); ++i)
      cell(VTK_LINE, {ids[i], ids[(i + 1) % n]}, component, kOutlineCell);
  }

  // The elements, and the couplings as lines from their reference node to
  // each node they tie (a frame's joint centres are couplings' reference
  // nodes: without them the joints would float beside the mesh).
  void mesh(const fe::Model& model, const std::function<Vec3(const Vec3&)>& place, int component) {
    const vtkIdType first = grid_->GetPoints()->GetNumberOfPoints();
    const vtkIdType added = append_mesh(*grid_, *kind_, model, place);
    for (vtkIdType k = 0; k < added; ++k) component_->InsertNextValue(component);
    auto idx = [&](fe::NodeId id) { return first + static_cast<vtkIdType>(model.node_index(id)); };
    for (const fe::RigidCoupling& c : model.couplings)
      for (fe::NodeId n : c.dependents) cell(VTK_LINE, {idx(c.reference), idx(n)}, component, kCouplingCell);
    for (const fe::DistributingCoupling& c : model.distributing_couplings)
      for (fe::NodeId n : c.nodes) cell(VTK_LINE, {idx(c.reference), idx(n)}, component, kCouplingCell);
  }

  vtkSmartPointer<vtkUnstructuredGrid> finish() {
    grid_->GetCellData()->AddArray(component_);
    grid_->GetCellData()->AddArray(kind_);
    grid_->GetCellData()->SetActiveScalars("component");
    return grid_;
  }

  vtkUnstructuredGrid& grid() { return *grid_; }

 private:
  vtkSmartPointer<vtkUnstructuredGrid> grid_ = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkIntArray> component_, kind_;
};

// Draws the frame; true when, having neither mesh nor interface nodes, it
// is drawn through its joints.
bool add_frame(AssemblyGrid& g, const std::optional<AssemblyFrame>& frame,
               const std::function<Vec3(const Vec3&)>& place, const std::vector<Vec3>& joints, int component) {
  if (frame && frame->mesh) {
    g.mesh(
        *frame->mesh, [&](const Vec3& x) { return place(x + frame->offset); }, component);
    return false;
  }
  if (frame && !frame->interface_nodes.empty()) {
    std::vector<Vec3> corners;
    for (const Vec3& x : frame->interface_nodes) corners.push_back(place(x + frame->offset));
    g.outline(corners, component);
    return false;
  }
  g.outline(joints, component);
  return true;
}

void add_body_box(AssemblyGrid& g, const fe::MassProperties& body, const rig::Kinematics& k) {
  const EquivalentBox box = equivalent_box(body);
  // VTK's hexahedron: the face at -z counter-clockwise, then the face at +z.
  static constexpr int kSigns[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                       {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  std::vector<vtkIdType> ids;
  for (const auto& s : kSigns) {
    Vec3 local = body.cog;
    for (int a = 0; a < 3; ++a) local += 0.5 * s[a] * box.sides(a) * box.axes.col(a);
    ids.push_back(g.point(k.r + k.R * local));
  }
  g.cell(VTK_HEXAHEDRON, ids, kBody, kBodyBoxCell);
  vtkNew<vtkDoubleArray> mass;
  mass->SetName("body_mass");
  mass->InsertNextValue(body.mass);
  vtkNew<vtkDoubleArray> sides;
  sides->SetName("box_sides");
  for (int a = 0; a < 3; ++a) sides->InsertNextValue(box.sides(a));
  g.grid().GetFieldData()->AddArray(mass);
  g.grid().GetFieldData()->AddArray(sides);
}

}  // namespace

AssemblyFrames assembly_frames(const rig::RigSpec& spec) {
  AssemblyFrames frames;
  for (const auto& e : spec.rig.effects) {
    const auto* pending = dynamic_cast<const rig::PendingFrame*>(e.get());
    if (!pending) continue;
    const rig::FrameSource& source = pending->source();
    AssemblyFrame f;
    f.offset = source.matching.offset;
    if (source.reduced) {
      for (const auto& node : source.reduced->interface_nodes) f.interface_nodes.push_back(node.position);
    } else {
      f.mesh = &source.model;
    }
    (source.fixed ? frames.fixed : frames.carrying) = f;
  }
  return frames;
}

EquivalentBox equivalent_box(const fe::MassProperties& body) {
  if (!(body.mass > 0)) throw std::invalid_argument("equivalent box: the body's mass must be positive");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(body.inertia);
  EquivalentBox box;
  box.axes = eig.eigenvectors();
  if (box.axes.determinant() < 0) box.axes.col(2) *= -1.0;
  const Vec3 J = eig.eigenvalues();
  for (int a = 0; a < 3; ++a) {
    const double square = 6.0 * (J.sum() - 2.0 * J(a)) / body.mass;
    box.sides(a) = square > 0 ? std::sqrt(square) : 0.0;
  }
  return box;
}

void add_rig_assembly_file(FileBatch& batch, const std::filesystem::path& file, const rig::RigSystem& rig,
                           const rig::Configuration& equilibrium, const AssemblyFrames& frames) {
  const rig::Kinematics k = rig.kinematics(equilibrium, rig.at_rest(), 0.0);
  std::vector<Vec3> upper, lower;
  for (const auto& r : k.rods) upper.push_back(r.A), lower.push_back(r.B);
  AssemblyGrid g;
  add_frame(
      g, frames.fixed, [](const Vec3& x) { return x; }, upper, kFixedFrame);
  for (size_t i = 0; i < upper.size(); ++i) g.cell(VTK_LINE, {g.point(upper[i]), g.point(lower[i])}, kRods, kRodCell);
  const auto in_g = [&](const Vec3& x_c) -> Vec3 { return k.r + k.R * x_c; };
  if (add_frame(g, frames.carrying, in_g, lower, kCarryingFrame)) {
    const vtkIdType p = g.point(k.r);
    for (const Vec3& b : lower) g.cell(VTK_LINE, {p, g.point(b)}, kCarryingFrame, kOutlineCell);
  }
  add_body_box(g, rig.assembly().body, k);
  // The meshes are drawn as built; the joints (and so the rods' ends) sit
  // where the loaded frames hold them. How far apart, for the reader:
  double fixed_deflection = 0, carrying_deflection = 0;
  const rig::RigGeometry& geometry = rig.assembly().geometry;
  for (size_t i = 0; i < k.rods.size(); ++i) {
    fixed_deflection = std::max(fixed_deflection, (k.rods[i].A - geometry.rods[i].upper).norm());
    carrying_deflection = std::max(carrying_deflection, (k.rods[i].lower_c - geometry.rods[i].lower).norm());
  }
  for (const auto& [name, value] : {std::pair{"fixed_frame_joint_deflection", fixed_deflection},
                                    {"carrying_frame_joint_deflection", carrying_deflection}}) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    g.grid().GetFieldData()->AddArray(a);
  }
  vtkSmartPointer<vtkUnstructuredGrid> grid = g.finish();
  batch.add(file, [grid](const std::filesystem::path& tmp) { write_vtu(grid, tmp, VtuEncoding::ascii); });
}

}  // namespace rigflex::io
