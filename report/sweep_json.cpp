#include "report/sweep_json.hpp"

#include <cstdio>

#include "report/json_write.hpp"

namespace rigflex::report {
namespace {

std::string number(const std::optional<double>& v) {
  if (!v) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", *v);
  return b;
}

// The common error summary, with the sets it pooled and Jyy's figures, which
// the sweep's plots and table follow, spelled out.
nlohmann::ordered_json errors_json(const std::optional<identify::ErrorSummary>& e) {
  if (!e) return nullptr;
  nlohmann::ordered_json j = {{"sets", e->sets}};
  add_error_summary(j, *e);
  j["Jyy_mean"] = e->moment_mean[1];
  j["Jyy_std"] = e->moment_std[1];
  return j;
}

}  // namespace

nlohmann::ordered_json sweep_json(const std::string& rig_name, const SweepSettings& settings,
                                  const std::vector<identify::SweepPoint>& points) {
  nlohmann::ordered_json pts = nlohmann::ordered_json::array();
  for (const auto& p : points) {
    pts.push_back({{"kind", identify::to_string(p.kind)},
                   {"scale", p.scale},
                   {"f1_hz", optional_number(p.f1_hz)},
                   {"swing_max_hz", optional_number(p.swing_max_hz)},
                   {"ratio", optional_number(p.ratio)},
                   {"rigid", errors_json(p.rigid)},
                   {"flexible", errors_json(p.flexible)},
                   {"failure", p.failure.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(p.failure)}});
  }
  nlohmann::ordered_json j;
  j["rig"] = rig_name;
  j["mass_scale"] = settings.mass_scale;
  j["stiffness_scale"] = settings.stiffness_scale;
  j["sets"] = settings.sets;
  j["histories"] = settings.histories;
  j["duration_s"] = settings.duration_s;
  j["seed"] = settings.seed;
  j["points"] = pts;
  return j;
}

std::string sweep_csv(const std::vector<identify::SweepPoint>& points) {
  std::string out =
      "kind,scale,f1_hz,swing_max_hz,ratio,rigid_zG_mean_m,rigid_zG_std_m,rigid_Jyy_mean,rigid_Jyy_std,"
      "flexible_zG_mean_m,flexible_zG_std_m,flexible_Jyy_mean,flexible_Jyy_std,failure\n";
  for (const auto& p : points) {
    out += std::string(identify::to_string(p.kind)) + "," + number(p.scale) + "," + number(p.f1_hz) + "," +
           number(p.swing_max_hz) + "," + number(p.ratio);
    for (const auto* e : {&p.rigid, &p.flexible}) {
      if (*e) {
        out += "," + number((*e)->zG_mean_m) + "," + number((*e)->zG_std_m) + "," + number((*e)->moment_mean[1]) +
               "," + number((*e)->moment_std[1]);
      } else {
        out += ",,,,";
      }
    }
    std::string why = p.failure;
    for (char& c : why) {
      if (c == ',' || c == '\n') c = ';';
    }
    out += "," + why + "\n";
  }
  return out;
}

}  // namespace rigflex::report
