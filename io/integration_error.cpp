#include "io/integration_error.hpp"

namespace rigflex::io {

std::runtime_error integration_error(const rig::IntegrationFailure& e, const rig::RigModel& model,
                                     const std::vector<std::filesystem::path>& model_files) {
  std::string files;
  for (const auto& f : model_files) files += (files.empty() ? "" : ", ") + f.string();
  std::string effects;
  for (const auto& x : model.effects) effects += (effects.empty() ? "" : ", ") + std::string(x->name());
  std::string text = files + ": the model's simulation stopped at t = " + std::to_string(e.time_s()) + " s (" +
                     e.method() + ": " + e.why() + "); effects in the model: " +
                     (effects.empty() ? std::string("none") : effects) + ". To try: ";
  if (model.simulation.method == rig::IntegrationMethod::generalized_alpha) {
    text += "`simulation: {method: bdf}` in the rig file (steps under error control), or `simulation.resolve_hz` "
            "above the frequency of the mode that fails (smaller fixed steps); ";
  } else {
    text += "`simulation.relative_tolerance` tighter or `simulation.max_step` smaller, or the default "
            "`method: generalized_alpha`; ";
  }
  text += "and check the effects' values: a stiffness or compliance far from the rig's own scale makes the "
          "equations stiff (`rigflex check` on the rig file shows its modes).";
  return std::runtime_error(text);
}

}  // namespace rigflex::io
