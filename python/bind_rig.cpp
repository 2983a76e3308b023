// Rigs, their measurements (simulated or read) and the design check's numbers.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/measurement_csv.hpp"
#include "io/rig_reader.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "rig/rig_system.hpp"
#include "rig/simulation.hpp"

namespace rigflex::python {
namespace {

rig::RigModel read_rig(const std::string& file, const std::vector<std::string>& effects) {
  rig::RigModel model;
  {
    py::gil_scoped_release unlocked;  // a frame given as an FE model is reduced here
    model = io::read_rig(file);
    for (const auto& f : effects) io::add_effects(model, f);
  }
  return model;
}

std::vector<std::vector<rig::Record>> simulate(const rig::RigModel& model, int sets, int histories, double duration,
                                               std::uint64_t seed) {
  rig::MeasurementOptions o;
  o.sets = sets;
  o.histories = histories;
  o.duration_s = duration;
  o.seed = seed;
  o.validate();
  py::gil_scoped_release unlocked;
  const rig::RigSystem system(model);
  return rig::simulate_measurement(system, o);
}

py::list read_measurements(const std::vector<std::string>& paths, int rods) {
  io::MeasurementSets sets;
  {
    py::gil_scoped_release unlocked;
    std::vector<std::filesystem::path> p(paths.begin(), paths.end());
    sets = io::read_measurement_sets(p, rods);
  }
  py::list out;
  for (auto& s : sets.sets) out.append(py::cast(std::move(s.records)));
  return out;
}

rig::Record make_record(const Eigen::VectorXd& t, const Eigen::MatrixXd& force, const Eigen::MatrixXd& alpha,
                        const Eigen::MatrixXd& beta) {
  if (force.rows() != t.size() || alpha.rows() != t.size() || beta.rows() != t.size())
    throw std::invalid_argument("Record: force, alpha and beta need a row per time sample");
  if (alpha.cols() != force.cols() || beta.cols() != force.cols())
    throw std::invalid_argument("Record: force, alpha and beta need a column per rod each");
  rig::Record r;
  r.t = t;
  r.force = force;
  r.alpha = alpha;
  r.beta = beta;
  r.sample_rate_hz = rig::nominal_sample_rate(t, {});
  return r;
}

}  // namespace

void bind_rig(py::module_& m) {
  py::class_<rig::RigModel>(m, "Rig", "A rig: geometry, body, rods, sensors and effects (docs/rig.md)")
      .def_readonly("name", &rig::RigModel::name)
      .def_property_readonly("rods", [](const rig::RigModel& r) { return r.geometry.rod_count(); })
      .def_property_readonly("body", [](const rig::RigModel& r) { return mass_properties(r.body); })
      .def_property_readonly("effects",
                             [](const rig::RigModel& r) {
                               std::vector<std::string> names;
                               for (const auto& e : r.effects) names.emplace_back(e->name());
                               return names;
                             })
      .def(
          "with_body",
          [](const rig::RigModel& r, std::optional<double> mass, std::optional<Eigen::Vector3d> cog,
             std::optional<Eigen::Matrix3d> inertia) {
            rig::RigModel copy = r;
            if (mass) copy.body.mass = *mass;
            if (cog) copy.body.cog = *cog;
            if (inertia) copy.body.inertia = *inertia;
            copy.validate_input();
            return copy;
          },
          py::arg("mass") = py::none(), py::arg("cog") = py::none(), py::arg("inertia") = py::none(),
          "A copy of the rig with the suspended body's mass (kg), CoG (m, frame c) or inertia tensor about the CoG "
          "(kg m^2) replaced; ValueError for a body no rig can hold (not positive definite, triangle inequality).")
      .def("__repr__", [](const rig::RigModel& r) {
        return "<rigflex.Rig '" + r.name + "', " + std::to_string(r.geometry.rod_count()) + " rods, " +
               std::to_string(r.body.mass) + " kg>";
      });
  py::class_<rig::Record>(m, "Record", "One history: time stamps and, per rod, load-cell force and encoder angles")
      .def(py::init(&make_record), py::arg("t"), py::arg("force"), py::arg("alpha"), py::arg("beta"))
      .def_readonly("t", &rig::Record::t)
      .def_readonly("force", &rig::Record::force)
      .def_readonly("alpha", &rig::Record::alpha)
      .def_readonly("beta", &rig::Record::beta)
      .def_readonly("sample_rate_hz", &rig::Record::sample_rate_hz)
      .def_property_readonly("file", [](const rig::Record& r) { return r.provenance.file; })
      .def("__repr__", [](const rig::Record& r) {
        return "<rigflex.Record " + std::to_string(r.samples()) + " samples x " + std::to_string(r.rods()) + " rods" +
               (r.provenance.file.empty() ? std::string() : ", " + r.provenance.file) + ">";
      });
  m.def("read_rig", &read_rig, py::arg("file"), py::arg("effects") = std::vector<std::string>{},
        "Reads a rig file and, optionally, effects files (as compare, diagnose and identify take them, e.g. the ones "
        "diagnose writes); errors name the file, line and key.");
  m.def("simulate", &simulate, py::arg("rig"), py::arg("sets") = 1, py::arg("histories") = 6,
        py::arg("duration") = 15.0, py::arg("seed") = 1,
        "A virtual measurement as `rigflex simulate` makes it: sets x histories of pushes and free swings with the "
        "sensors' noise; a list of sets, each a list of Records. Deterministic for a seed.");
  m.def("read_measurements", &read_measurements, py::arg("paths"), py::arg("rods") = 0,
        "Measurement files per the data contract (docs/measurement-files.md): a folder of .csv (.csv.gz) files is "
        "a set, a folder of such folders one set each, files given directly one set; a list of sets of Records.");
}

}  // namespace rigflex::python
