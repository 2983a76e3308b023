#pragma once
// check.json: the design check (swing and deformation modes, ratio, verdicts,
// strain-energy shares, stiffening advice) and the predicted identification
// error. Keys sorted (nlohmann::json).
#include <nlohmann/json.hpp>
#include <optional>

#include "identify/predicted_error.hpp"
#include "rig/design_check.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::report {

// `prediction` is absent when the check ran without a virtual measurement;
// `conclusion` is identify::conclude_check of the two.
nlohmann::json check_json(const rig::RigModel& model, const rig::CheckResult& check,
                          const std::optional<identify::Prediction>& prediction,
                          const identify::CheckConclusion& conclusion);

}  // namespace rigflex::report
