#include "report/modes_json.hpp"

#include "io/mass_record.hpp"

namespace rigflex::report {

nlohmann::json modes_json(const std::string& model_name, const reduction::ModalAnalysis& a) {
  const auto& r = a.result;
  const auto& s = a.summary;
  nlohmann::json modes = nlohmann::json::array();
  nlohmann::json freqs = nlohmann::json::array();
  static const char* dirs[6] = {"TX", "TY", "TZ", "RX", "RY", "RZ"};
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    auto by_direction = [&](const Eigen::MatrixXd& x) {
      nlohmann::json o = nlohmann::json::object();
      for (int d = 0; d < 6; ++d) o[dirs[d]] = x(k, d);
      return o;
    };
    freqs.push_back(s.frequencies_hz(k));
    modes.push_back({{"mode", k + 1},
                     {"frequency_hz", s.frequencies_hz(k)},
                     {"eigenvalue", r.eigenvalues(k)},
                     {"modal_mass", s.modal_mass(k)},
                     {"translation_share", s.translation_share(k)},
                     {"drilling_share", s.drilling_share(k)},
                     {"participation_factor", by_direction(s.participation)},
                     {"effective_mass", by_direction(s.effective_mass)},
                     {"effective_mass_fraction", by_direction(s.effective_mass_fraction)},
                     {"cumulative_effective_mass_fraction", by_direction(s.cumulative_fraction)},
                     {"residual", r.residuals(k)},
                     {"backward_error", r.backward_errors(k)}});
  }
  nlohmann::json warnings = nlohmann::json::array(), notes = nlohmann::json::array();
  for (const auto& w : reduction::rotation_only_modes(s, a.mass.mass)) {
    (w.drilling ? warnings : notes).push_back(describe(w, s));
  }
  return {{"model", model_name},
          {"dofs", a.system.dofs.free_count()},
          {"mass_properties", io::mass_properties_json(a.mass)},
          {"solver",
           {{"method", "shift-invert Lanczos, thick restart, full M-reorthogonalization (CHOLMOD)"},
            {"converged", r.converged},
            {"requested", r.requested},
            {"converged_count", r.converged_count},
            {"shift", r.shift},
            {"block_size", r.block_size},
            {"restarts", r.restarts},
            {"automatic_retries", r.retries},
            {"first_attempt", r.first_attempt},
            {"operator_applications", r.operator_applications},
            {"max_residual", r.residuals.size() ? r.residuals.maxCoeff() : 0.0},
            {"max_backward_error", r.backward_errors.size() ? r.backward_errors.maxCoeff() : 0.0},
            {"orthogonality_error", r.orthogonality_error},
            {"message", r.message}}},
          {"warnings", warnings},
          {"notes", notes},
          {"frequencies_hz", freqs},
          {"modes", modes}};
}

}  // namespace rigflex::report
