#pragma once
// Small conversions shared by the bindings.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>

#include "fe/mass_properties.hpp"

namespace rigflex::python {

namespace py = pybind11;

// {"mass": kg, "cog": array(3) m, "inertia": array(3, 3) kg m^2 about the CoG}.
inline py::dict mass_properties(const fe::MassProperties& p) {
  py::dict d;
  d["mass"] = p.mass;
  d["cog"] = Eigen::VectorXd(p.cog);
  d["inertia"] = Eigen::MatrixXd(p.inertia);
  return d;
}

}  // namespace rigflex::python
