#include "report/check_json.hpp"

#include "report/json_write.hpp"

namespace rigflex::report {

nlohmann::json check_json(const rig::RigModel& model, const rig::CheckResult& r,
                          const std::optional<identify::Prediction>& p, const identify::CheckConclusion& c) {
  nlohmann::json j;
  j["rig"] = model.name;
  j["swing_frequencies_hz"] = r.swing_frequencies_hz;
  j["first_deformation_frequency_hz"] = optional_number<nlohmann::json>(r.first_deformation_frequency_hz);
  j["ratio"] = optional_number<nlohmann::json>(r.ratio);
  j["verdict"] = rig::to_string(c.verdict);
  j["verdict_reason"] = c.reason;
  j["ratio_verdict"] = rig::to_string(r.verdict);
  if (p) {
    nlohmann::json pe = {{"algorithm", "rigid"},
                         {"sets", p->sets},
                         {"histories", p->histories},
                         {"duration_s", p->duration_s},
                         {"observable", p->unobservable.empty()}};
    if (p->rigid) {
      pe.update(error_summary_json<nlohmann::json>(*p->rigid));
    } else {
      pe["zG_mean_m"] = nullptr;
      pe["zG_std_m"] = nullptr;
      pe["unobservable"] = p->unobservable;
    }
    if (p->from_flexibility) pe["from_flexibility"] = error_summary_json<nlohmann::json>(*p->from_flexibility);
    if (p->flexible) pe["flexible_algorithm"] = error_summary_json<nlohmann::json>(*p->flexible);
    pe["verdict"] = rig::to_string(p->verdict);
    if (!p->note.empty()) pe["note"] = p->note;
    j["predicted_error"] = pe;
  }
  j["strain_energy_share"] = {{"fixed_frame", r.share_fixed_frame},
                              {"rods", r.share_rods},
                              {"carrying_frame", r.share_carrying_frame}};
  if (c.advice) {
    j["stiffen"] = {{"component", rig::to_string(c.advice->component)},
                    {"stiffness_factor", optional_number<nlohmann::json>(c.advice->factor)},
                    {"because_of", c.advice_reason},
                    {"message", c.advice->message}};
    if (c.advice_reason == "frequency ratio") j["stiffen"]["ratio_with_component_1e4_stiffer"] = c.advice->ratio_limit;
  }
  nlohmann::json modes = nlohmann::json::array();
  for (const auto& m : r.linearization.modes) {
    const double total = m.strain.total();
    modes.push_back({{"frequency_hz", m.frequency_hz},
                     {"kind", rig::to_string(m.kind)},
                     {"elastic_fraction", m.elastic_fraction},
                     {"body_fraction", m.body_fraction},
                     {"strain_energy_share",
                      {{"fixed_frame", total > 0 ? m.strain.fixed_frame / total : 0.0},
                       {"rods", total > 0 ? m.strain.rods / total : 0.0},
                       {"carrying_frame", total > 0 ? m.strain.carrying_frame / total : 0.0}}}});
  }
  j["modes"] = modes;
  const auto& eq = r.linearization.equilibrium;
  j["equilibrium"] = {{"steps", eq.iterations}, {"residual", eq.residual}};
  j["eigen_check"] = {{"max_residual", r.linearization.eigen.residuals.maxCoeff()},
                      {"orthogonality_error", r.linearization.eigen.orthogonality_error},
                      {"stiffness_asymmetry", r.linearization.asymmetry}};
  return j;
}

}  // namespace rigflex::report
