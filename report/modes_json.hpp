#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "fe/mass_properties.hpp"
#include "reduction/modal_analysis.hpp"

namespace rigflex::report {

// modes.json: frequencies_hz, per-mode records with modal mass, effective
// mass fractions, residual and orthogonality; solver status.
nlohmann::json modes_json(const std::string& model_name, const reduction::ModalAnalysis& a);

}  // namespace rigflex::report
