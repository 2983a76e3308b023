// compare and diagnose, as the commands run them: the same documents as
// compare.json and diagnosis.json, with the model's predicted histories.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "diagnose/diagnosis.hpp"
#include "diagnose/model_comparison.hpp"
#include "diagnose/model_response.hpp"
#include "python/bindings.hpp"
#include "report/compare_json.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::python {
namespace {

using Histories = std::vector<rig::Record>;

std::vector<const rig::Record*> pointers(const Histories& records) {
  if (records.empty()) throw std::invalid_argument("no history given");
  std::vector<const rig::Record*> p;
  for (const auto& r : records) p.push_back(&r);
  return p;
}

std::vector<std::string> sources(const Histories& records) {
  std::vector<std::string> s;
  for (size_t k = 0; k < records.size(); ++k)
    s.push_back(records[k].provenance.file.empty() ? "history " + std::to_string(k + 1) : records[k].provenance.file);
  return s;
}

report::CompareContext context(const rig::RigModel& model) {
  report::CompareContext ctx;
  ctx.rig = model.name;
  ctx.model_label = model.name;
  for (const auto& e : model.effects) ctx.model_effects.emplace_back(e->name());
  return ctx;
}

py::object compare(const rig::RigModel& model, const Histories& records, bool hold_body, int threads) {
  diagnose::ModelComparisonOptions o;
  o.fit_model = !hold_body;
  o.threads = threads;
  diagnose::ModelComparison c;
  {
    py::gil_scoped_release unlocked;
    const diagnose::ResponseModel response(model);
    c = diagnose::compare_model(response, pointers(records), sources(records), o);
  }
  py::dict d(to_python(report::compare_json(c, context(model))));
  py::list predicted;  // the model's channels per history: F per rod, then alpha, then beta
  for (const auto& h : c.histories) predicted.append(py::cast(h.model));
  d["model_channels"] = predicted;
  d["channels"] = c.channels;
  return d;
}

py::object diagnose_rig(const rig::RigModel& model, const Histories& records, const std::vector<std::string>& only,
                        int max_effects, double period_tolerance, int threads) {
  diagnose::DiagnosisOptions o;
  o.effects = only;
  if (max_effects > 0) o.max_effects = max_effects;
  o.period_tolerance = period_tolerance;
  o.threads = threads;
  o.validate();
  diagnose::Diagnosis d;
  {
    py::gil_scoped_release unlocked;
    d = diagnose::diagnose(model, pointers(records), sources(records), o);
  }
  return to_python(report::diagnosis_json(d, context(model)));
}

}  // namespace

void bind_diagnose(py::module_& m) {
  m.def("compare", &compare, py::arg("rig"), py::arg("records"), py::arg("hold_body") = false, py::arg("threads") = 0,
        "The rig's model beside the records (a list of Records): the swing state fitted per history, the body's "
        "mass properties refitted (not with hold_body), errors per channel and history, residual analysis and the "
        "identification - compare.json's document, with the model's channels per history ('model_channels').");
  m.def("diagnose", &diagnose_rig, py::arg("rig"), py::arg("records"), py::arg("only") = std::vector<std::string>{},
        py::arg("max_effects") = 0, py::arg("period_tolerance") = diagnose::DiagnosisOptions{}.period_tolerance,
        py::arg("threads") = 0,
        "Which catalogue effect the records hold that the rig lacks: every candidate fitted with the body, ranked, "
        "tested, chained - diagnosis.json's document ('summary', 'missing_effect', 'ranking', 'chain', ...). "
        "period_tolerance: the swing period error the records' simulator may have, allowed in the gate "
        "('baseline': 'gate', 'numerics_allowance'); 0 for records from a real rig.");
}

}  // namespace rigflex::python
