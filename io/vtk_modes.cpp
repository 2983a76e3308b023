#include "io/vtk_modes.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "fe/bounding_box.hpp"
#include "fe/shell_centres.hpp"
#include "io/vtk_mesh.hpp"

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {

vtkSmartPointer<vtkUnstructuredGrid> mesh_grid(const fe::Model& model) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  grid->SetPoints(points);
  vtkNew<vtkIntArray> kind;  // 1 beam, 2 shell, 3 point mass, 4 solid: lets ParaView threshold by element kind
  kind->SetName("element_kind");
  append_mesh(*grid, *kind, model, [](const Eigen::Vector3d& x) { return x; });
  grid->GetCellData()->AddArray(kind);
  return grid;
}

// The model's size for display: its bounding box's largest side (1 for a
// model of one point).
double model_extent(const fe::Model& model) {
  const double d = fe::bounding_box_sides(model).maxCoeff();
  return d > 0 ? d : 1.0;
}

}  // namespace

double display_scale(const Eigen::VectorXd& full, double extent) {
  double largest = 0;  // translation, or rotation times the extent: what a rotation moves the model's far end by
  for (Eigen::Index b = 0; b + 5 < full.size(); b += 6) {
    largest = std::max({largest, full.segment<3>(b).norm(), extent * full.segment<3>(b + 3).norm()});
  }
  return largest > 0 ? kDisplayShare * extent / largest : 1.0;
}

std::string mode_collection(const Eigen::VectorXd& f, const std::vector<std::string>& files) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  o.precision(10);
  for (size_t i = 0; i < files.size(); ++i)
    o << "    <DataSet timestep=\"" << i + 1 << "\" part=\"0\" name=\"mode " << i + 1 << " " << f(static_cast<Eigen::Index>(i))
      << " Hz\" file=\"" << files[i] << "\"/>\n";
  o << "  </Collection>\n</VTKFile>\n";
  return o.str();
}

void add_mode_shape_files(FileBatch& batch, const fs::path& dir, const fe::Model& model, const fe::DofMap& dofs,
                          const Eigen::VectorXd& frequencies_hz, const Eigen::MatrixXd& vectors) {
  std::vector<std::string> names;
  const std::vector<fe::NodeId> coordinates = fe::coordinate_nodes(model);
  for (Eigen::Index k = 0; k < vectors.cols(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "mode_%03ld.vtu", static_cast<long>(k + 1));
    names.emplace_back(name);
    const double f = frequencies_hz(k);
    Eigen::VectorXd normalized = dofs.expand(vectors.col(k));
    // Element coordinates are no displacement of a point: drawn as rest.
    for (fe::NodeId id : coordinates)
      normalized.segment<6>(6 * static_cast<Eigen::Index>(model.node_index(id))).setZero();
    const double scale = display_scale(normalized, model_extent(model));
    const Eigen::VectorXd full = scale * normalized;
    batch.add(dir / name, [&model, full, f, k, scale](const fs::path& tmp) {
      auto grid = mesh_grid(model);
      vtkNew<vtkDoubleArray> u, r;
      u->SetName("translation");
      r->SetName("rotation");
      u->SetNumberOfComponents(3);
      r->SetNumberOfComponents(3);
      for (size_t i = 0; i < model.nodes.size(); ++i) {
        const auto b = static_cast<Eigen::Index>(6 * i);
        u->InsertNextTuple3(full(b), full(b + 1), full(b + 2));
        r->InsertNextTuple3(full(b + 3), full(b + 4), full(b + 5));
      }
      grid->GetPointData()->AddArray(u);
      grid->GetPointData()->AddArray(r);
      grid->GetPointData()->SetActiveVectors("translation");
      vtkNew<vtkDoubleArray> freq;
      freq->SetName("frequency_hz");
      freq->InsertNextValue(f);
      vtkNew<vtkIntArray> mode;
      mode->SetName("mode");
      mode->InsertNextValue(static_cast<int>(k + 1));
      vtkNew<vtkDoubleArray> shown;
      shown->SetName("display_scale");
      shown->InsertNextValue(scale);
      grid->GetFieldData()->AddArray(freq);
      grid->GetFieldData()->AddArray(mode);
      grid->GetFieldData()->AddArray(shown);
      write_vtu(grid, tmp, VtuEncoding::appended);
    });
  }
  batch.add_text(dir / "modes.pvd", mode_collection(frequencies_hz, names));
}

}  // namespace rigflex::io
