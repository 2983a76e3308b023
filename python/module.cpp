// import rigflex: the library from Python (docs/python.md).
#include <stdexcept>

#include "fe/error.hpp"
#include "io/input_error.hpp"
#include "python/bindings.hpp"

namespace rigflex::python {

py::object to_python(const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::ordered_json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v);
      return d;
    }
    case nlohmann::ordered_json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(to_python(v));
      return l;
    }
    case nlohmann::ordered_json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::ordered_json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer:
    case nlohmann::ordered_json::value_t::number_unsigned:
      return py::int_(j.get<long long>());
    case nlohmann::ordered_json::value_t::number_float:
      return py::float_(j.get<double>());
    default:
      return py::none();
  }
}

}  // namespace rigflex::python

namespace py = pybind11;

PYBIND11_MODULE(_rigflex, m) {
  namespace rp = rigflex::python;
  m.doc() =
      "rigflex: flexible models of multi-filar pendulum rigs - FE frames, modes, reduction, rig simulation, "
      "identification, compare and diagnose";
  // Bad input names its file, line and key as on the command line: a ValueError.
  py::register_exception<rigflex::io::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<rigflex::fe::ModelError>(m, "ModelError", PyExc_ValueError);
  rp::bind_models(m);
  rp::bind_reduction(m);
  rp::bind_rig(m);
  rp::bind_identify(m);
  rp::bind_diagnose(m);
}
