// Models, their assembled matrices and their modes.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "fe/assembly.hpp"
#include "io/model_reader.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "reduction/ill_determined_modes.hpp"
#include "reduction/modal_analysis.hpp"
#include "reduction/zero_frequency_modes.hpp"

namespace rigflex::python {
namespace {

std::vector<std::string> dof_names(const fe::DofMap& dofs) {
  std::vector<std::string> names;
  names.reserve(static_cast<size_t>(dofs.free_count()));
  for (Eigen::Index k = 0; k < dofs.free_count(); ++k) names.push_back(dofs.describe(k));
  return names;
}

py::dict assemble(const io::ModelFile& m) {
  fe::AssembledSystem s;
  {
    py::gil_scoped_release unlocked;
    s = fe::assemble(m.model);
  }
  py::dict d;
  d["K"] = s.K;
  d["M"] = s.M;
  d["dofs"] = dof_names(s.dofs);
  return d;
}

py::dict modes(const io::ModelFile& m, int count, std::optional<double> shift_hz) {
  linalg::EigenOptions opt;
  opt.count = count;
  if (shift_hz) opt.shift = -std::pow(2 * std::numbers::pi * *shift_hz, 2);
  reduction::ModalAnalysis a;
  {
    py::gil_scoped_release unlocked;
    a = reduction::run_modal_analysis(m.model, opt);
  }
  if (!a.mechanism.empty()) {
    std::string dofs;
    for (const auto& f : a.mechanism) dofs += (dofs.empty() ? "" : ", ") + f;
    throw std::runtime_error(m.name + ": the model is a mechanism (K - sigma M is singular); free DOFs: " + dofs);
  }
  if (!a.result.converged) throw std::runtime_error(m.name + ": the eigen solver stopped: " + a.result.message);
  py::dict d;
  d["frequencies_hz"] = a.summary.frequencies_hz;
  d["shapes"] = a.result.vectors;  // free DOFs x modes, M-orthonormal
  d["modal_mass"] = a.summary.modal_mass;
  d["effective_mass_fraction"] = a.summary.effective_mass_fraction;  // modes x (TX TY TZ RX RY RZ)
  d["residuals"] = a.result.residuals;
  d["backward_errors"] = a.result.backward_errors;
  d["orthogonality_error"] = a.result.orthogonality_error;
  d["dofs"] = dof_names(a.system.dofs);
  d["mass"] = mass_properties(a.mass);
  // As modes.json: the modes of zero frequency, and the flexible modes whose
  // frequency double precision gives to worse than 1e-6 (1-based).
  const std::vector<reduction::ZeroFrequencyMode> zero = reduction::zero_frequency_modes(m.model, a);
  py::list zero_modes, vague;
  for (const auto& z : zero) zero_modes.append(z.mode + 1);
  for (const auto& v : reduction::ill_determined_modes(a, zero)) {
    py::dict e;
    e["mode"] = v.mode + 1;
    e["relative_error"] = v.relative_error;
    vague.append(e);
  }
  d["zero_frequency_modes"] = zero_modes;
  d["ill_determined_modes"] = vague;
  return d;
}

}  // namespace

void bind_models(py::module_& m) {
  py::class_<io::ModelFile>(m, "Model", "A finite-element model read from a model file (docs/fe-core.md)")
      .def_readonly("name", &io::ModelFile::name)
      .def_property_readonly("nodes", [](const io::ModelFile& f) { return f.model.nodes.size(); })
      .def("__repr__", [](const io::ModelFile& f) {
        return "<rigflex.Model '" + f.name + "', " + std::to_string(f.model.nodes.size()) + " nodes>";
      });
  m.def(
      "read_model", [](const std::string& file) { return io::read_model(file); }, py::arg("file"),
      "Reads a model file (rigflex YAML, Abaqus/CalculiX .inp, Gmsh .msh); errors name the file, line and key.");
  m.def("assemble", &assemble, py::arg("model"),
        "The stiffness K and mass M on the free DOFs (supports removed, couplings eliminated) as scipy.sparse "
        "matrices, and the DOFs' names.");
  m.def("modes", &modes, py::arg("model"), py::arg("count") = 10, py::arg("shift_hz") = py::none(),
        "The lowest `count` modes by rigflex's shift-invert Lanczos: frequencies_hz, M-orthonormal shapes over the "
        "free DOFs, modal masses, effective mass fractions, residuals and the M-orthonormality error, as "
        "`rigflex modes` prints them.");
}

}  // namespace rigflex::python
