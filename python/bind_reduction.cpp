// Reduction of a frame onto its joints (Guyan, Craig-Bampton), as `rigflex reduce`.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>

#include "fe/dof.hpp"
#include "io/model_reader.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "reduction/frame_reduction.hpp"

namespace rigflex::python {
namespace {

template <typename T>
T parsed(const std::optional<T>& v, const char* option, const std::string& given) {
  if (!v) throw std::invalid_argument(std::string(option) + ": unknown value '" + given + "'");
  return *v;
}

py::dict checks_dict(const reduction::ReductionChecks& c) {
  py::list frequencies;
  for (const auto& f : c.frequencies) {
    py::dict d;
    d["mode"] = f.mode;
    d["full_hz"] = f.full_hz;
    d["reduced_hz"] = f.reduced_hz;
    d["error_percent"] = f.error_percent;
    d["mac"] = f.mac;
    frequencies.append(d);
  }
  py::dict d;
  d["frequencies"] = frequencies;
  d["mac"] = c.mac;
  d["rigid_body_modes_full"] = c.rigid_body_modes_full;
  d["rigid_body_modes_reduced"] = c.rigid_body_modes_reduced;
  d["static_flexibility_error"] = c.static_flexibility_error;
  d["reduced_frequencies_hz"] = c.reduced_frequencies_hz;
  d["damping_ratios"] = c.damping_ratios;
  return d;
}

py::dict reduce(const io::ModelFile& m, const std::string& interface_set, const std::string& method, int modes,
                std::optional<double> cutoff_hz, const std::string& dofs, double zeta) {
  reduction::FrameReductionOptions o;
  o.interface_set = interface_set;
  o.method = parsed(reduction::parse_reduction_method(method), "method", method);
  o.retained = parsed(reduction::parse_interface_dofs(dofs), "dofs", dofs);
  o.modes = modes;
  o.cutoff_hz = cutoff_hz;
  o.zeta = zeta;
  o.validate();
  reduction::ReducedFrame r;
  {
    py::gil_scoped_release unlocked;
    r = reduction::reduce_frame(m.model, o);
  }
  std::vector<std::string> names;
  for (const auto& d : r.interface_dofs)
    names.push_back("node " + std::to_string(d.node) + " " + std::string(fe::dof_name(d.local)));
  py::dict ss;
  ss["A"] = r.state_space.A;
  ss["B"] = r.state_space.B;
  ss["C"] = r.state_space.C;
  ss["D"] = r.state_space.D;
  ss["T"] = r.state_space.T;
  ss["coordinates"] = reduction::to_string(r.state_space.coordinates);
  py::dict d;
  d["name"] = r.name;
  d["method"] = reduction::to_string(r.method);
  d["support"] = reduction::to_string(r.support);
  d["K"] = r.K;
  d["M"] = r.M;
  d["C"] = r.C;
  d["interface_dofs"] = names;  // the first rows of K, M, C; then the modal coordinates
  d["mode_frequencies_hz"] = r.mode_frequencies_hz;
  d["state_space"] = ss;
  d["checks"] = checks_dict(r.checks);
  d["full_free_dofs"] = r.full_free_dofs;
  return d;
}

}  // namespace

void bind_reduction(py::module_& m) {
  m.def("reduce", &reduce, py::arg("model"), py::arg("interface"), py::arg("method") = "guyan", py::arg("modes") = 0,
        py::arg("cutoff_hz") = py::none(), py::arg("dofs") = "all", py::arg("zeta") = 0.02,
        "Reduces a frame onto the node set `interface` (its joint centres) by Guyan or Craig-Bampton "
        "(`modes` fixed-interface modes, or all below `cutoff_hz`), with Rayleigh damping `zeta` from elastic modes "
        "1 and 3: K, M, C, the interface DOFs' names, the state space and the checks, as `rigflex reduce` writes "
        "them.");
}

}  // namespace rigflex::python
