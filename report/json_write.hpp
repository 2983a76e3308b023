#pragma once
// Writing numbers into the tools' JSON: JSON has no NaN or infinity, so a
// non-finite value (an undefined error, a missing statistic) is written null.
#include <cmath>
#include <nlohmann/json.hpp>

namespace rigflex::report {

inline nlohmann::ordered_json finite_or_null(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

}  // namespace rigflex::report
