// Identification of mass properties from free swings, as `rigflex identify`:
// one least-squares solve per set, each history alone (the tests), the
// statistics over them - the same document as identification.json.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "identify/identification.hpp"
#include "python/bindings.hpp"
#include "report/identification_report.hpp"
#include "report/identify_sets.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::python {
namespace {

using Sets = std::vector<std::vector<rig::Record>>;

identify::IdentificationOptions options_from(std::optional<std::vector<double>> static_cog) {
  identify::IdentificationOptions o;
  if (static_cog) {
    if (static_cog->size() == 2) {
      o.cog_constraint = identify::CogConstraint::in_plane;
      o.imposed_cog = rig::Vec3((*static_cog)[0], (*static_cog)[1], 0.0);
    } else if (static_cog->size() == 3) {
      o.cog_constraint = identify::CogConstraint::full;
      o.imposed_cog = rig::Vec3((*static_cog)[0], (*static_cog)[1], (*static_cog)[2]);
    } else {
      throw std::invalid_argument("static_cog: expected [x, y] or [x, y, z] in metres");
    }
  }
  o.validate();
  return o;
}

std::vector<std::string> files_of(const std::vector<rig::Record>& set, size_t k) {
  std::vector<std::string> files;
  for (size_t h = 0; h < set.size(); ++h)
    files.push_back(set[h].provenance.file.empty()
                        ? "set " + std::to_string(k + 1) + " history " + std::to_string(h + 1)
                        : set[h].provenance.file);
  return files;
}

py::object identify_sets(const rig::RigModel& model, const Sets& sets, const std::string& algorithm,
                         std::optional<std::vector<double>> static_cog) {
  report::algorithms_of(algorithm);  // a bad choice is refused before any work
  if (sets.empty()) throw std::invalid_argument("identify: no measurement set");
  report::IdentificationReport rep;
  rep.rig = model.name;
  rep.options = options_from(static_cog);
  if (static_cog && static_cog->size() == 3) rep.static_cog_height = (*static_cog)[2];
  for (size_t k = 0; k < sets.size(); ++k) {
    if (sets[k].empty()) throw std::invalid_argument("identify: set " + std::to_string(k + 1) + " has no history");
    rep.set_names.push_back("set" + std::to_string(k + 1));
    rep.set_files.push_back(files_of(sets[k], k));
  }
  report::IdentifySetsOptions io_options;
  io_options.algorithm = algorithm;
  std::vector<std::vector<const rig::Record*>> ptrs(sets.size());
  for (size_t k = 0; k < sets.size(); ++k) {
    for (const auto& r : sets[k]) ptrs[k].push_back(&r);
  }
  {
    py::gil_scoped_release unlocked;
    try {
      report::identify_sets(model, ptrs, io_options, rep);
    } catch (const report::SetError& e) {
      if (e.record()) throw *e.record();
      throw std::invalid_argument(rep.set_names[e.set()] + ": " + e.what());
    }
  }
  return to_python(rep.json());
}

}  // namespace

void bind_identify(py::module_& m) {
  m.def("identify", &identify_sets, py::arg("rig"), py::arg("sets"), py::arg("algorithm") = "rigid",
        py::arg("static_cog") = py::none(),
        "Mass properties from measured free swings (a list of sets, each a list of Records): per set the least "
        "squares of the Newton-Euler equations, each history alone, and the statistics - the document "
        "identification.json holds ('mean', 'sets', 'tests', with both algorithms 'algorithms' and 'comparison'). "
        "static_cog: [x, y] or [x, y, z] from the static procedure, imposed.");
}

}  // namespace rigflex::python
