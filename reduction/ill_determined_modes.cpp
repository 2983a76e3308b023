#include "reduction/ill_determined_modes.hpp"

#include <algorithm>
#include <cstdio>

namespace rigflex::reduction {

std::vector<IllDeterminedMode> ill_determined_modes(const ModalAnalysis& a, const std::vector<ZeroFrequencyMode>& zero,
                                                    double limit) {
  std::vector<IllDeterminedMode> out;
  const Eigen::VectorXd f = a.result.frequencies_hz();
  for (Eigen::Index k = 0; k < a.result.residuals.size(); ++k) {
    if (std::any_of(zero.begin(), zero.end(), [k](const ZeroFrequencyMode& z) { return z.mode == k; })) continue;
    const double error = 0.5 * a.result.residuals(k);
    if (error > limit) out.push_back({k, f(k), error});
  }
  return out;
}

double stiffest_ratio(const fe::AssembledSystem& s) {
  const Eigen::VectorXd k = s.K.diagonal(), m = s.M.diagonal();
  double r = 0;
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    if (m(i) > 0) r = std::max(r, k(i) / m(i));
  }
  return r;
}

std::string describe(const std::vector<IllDeterminedMode>& modes, const ModalAnalysis& a) {
  if (modes.empty()) return "";
  char buf[160];
  std::string s = modes.size() == 1 ? "mode " : "modes ";
  double worst = 0, lambda = a.result.eigenvalues(modes.front().mode);
  for (size_t i = 0; i < modes.size(); ++i) {
    s += (i ? ", " : "") + std::to_string(modes[i].mode + 1);
    worst = std::max(worst, modes[i].relative_error);
    lambda = std::min(lambda, a.result.eigenvalues(modes[i].mode));
  }
  std::snprintf(buf, sizeof buf, ": frequencies determined only to about %.1e relative in double precision", worst);
  s += buf;
  const double ratio = stiffest_ratio(a.system);
  if (lambda > 0 && ratio > 0) {
    std::snprintf(buf, sizeof buf, " (the stiffest DOF's K_ii / M_ii is %.1e x the lowest such eigenvalue)",
                  ratio / lambda);
    s += buf;
  }
  s += "; the model joins very stiff and very soft parts, and any solver's values may differ by that much. Where a "
       "stiff element or spring stands in for a rigid connection, a rigid coupling removes it";
  return s;
}

}  // namespace rigflex::reduction
