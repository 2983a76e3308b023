#pragma once
// Writing numbers and shared records into the tools' JSON. JSON has no NaN or
// infinity, so a non-finite value (an undefined error, a missing statistic)
// is written null, and so is an absent optional value. The helpers are
// templates over nlohmann's json (keys sorted) and ordered_json (keys in
// insertion order), since results use both.
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "identify/virtual_identification.hpp"

namespace rigflex::report {

inline nlohmann::ordered_json finite_or_null(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

template <class Json = nlohmann::ordered_json>
Json optional_number(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

// The one schema of an identification error summary (check.json's predicted
// error, sweep.json's points): errors of identified against reference mass
// properties, zG in m, moments relative, products relative to the largest
// moment, in-plane CoG in m. Added to `j` in this order.
template <class Json>
void add_error_summary(Json& j, const identify::ErrorSummary& e) {
  j["zG_mean_m"] = e.zG_mean_m;
  j["zG_std_m"] = e.zG_std_m;
  j["moment_mean"] = e.moment_mean;
  j["moment_std"] = e.moment_std;
  j["product_max_of_largest"] = e.product_max;
  j["cog_in_plane_max_m"] = e.cog_in_plane_max_m;
}

template <class Json = nlohmann::ordered_json>
Json error_summary_json(const identify::ErrorSummary& e) {
  Json j = Json::object();
  add_error_summary(j, e);
  return j;
}

}  // namespace rigflex::report
