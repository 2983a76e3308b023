#pragma once
// sweep.json and sweep.csv: the identification error of each sweep point
// (identify/sweep.hpp), with the settings the sweep ran with.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "identify/sweep.hpp"

namespace rigflex::report {

// What the sweep was asked for, as the user wrote it.
struct SweepSettings {
  std::string mass_scale, stiffness_scale;  // start:stop:count
  int sets = 0, histories = 0;
  double duration_s = 0;
  unsigned long long seed = 0;
};

nlohmann::ordered_json sweep_json(const std::string& rig_name, const SweepSettings& settings,
                                  const std::vector<identify::SweepPoint>& points);
// One row per point: zG and Jyy errors of both algorithms, empty where a
// point failed (its reason in the last column, commas replaced).
std::string sweep_csv(const std::vector<identify::SweepPoint>& points);

}  // namespace rigflex::report
