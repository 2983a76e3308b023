#pragma once
// The Python module's parts (python/module.cpp): each binds one stage of the
// pipeline. Conversions: Eigen dense <-> NumPy and Eigen sparse <-> SciPy
// sparse through pybind11/eigen.h; results as dicts of NumPy arrays and
// numbers; JSON documents (the CLI's .json files) as nested dicts and lists.
// Long calls release the GIL while the C++ work runs.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace rigflex::python {

namespace py = pybind11;

void bind_models(py::module_& m);     // read_model, Model, assemble, modes
void bind_reduction(py::module_& m);  // reduce
void bind_rig(py::module_& m);        // read_rig, Rig, simulate, read_measurements
void bind_identify(py::module_& m);   // identify
void bind_diagnose(py::module_& m);   // compare, diagnose

// A JSON document as Python objects (dict, list, str, float, int, bool, None).
py::object to_python(const nlohmann::ordered_json& j);

}  // namespace rigflex::python
