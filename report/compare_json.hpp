#pragma once
// JSON of `rigflex compare` (compare.json) and `rigflex diagnose`
// (diagnosis.json); the keys are documented in docs/compare.md. Numbers are
// SI; non-finite values are written as null.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fe/mass_properties.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/model_comparison.hpp"

namespace rigflex::report {

struct CompareContext {
  std::string rig;                       // rig name
  std::string model_label;               // rig file + added effects files
  std::vector<std::string> model_effects;
  std::optional<fe::MassProperties> reference;  // static reference, if given
};

nlohmann::ordered_json compare_json(const diagnose::ModelComparison& c, const CompareContext& context);
nlohmann::ordered_json diagnosis_json(const diagnose::Diagnosis& d, const CompareContext& context);

}  // namespace rigflex::report
