#include "identify/predicted_error.hpp"

#include <algorithm>
#include <cmath>

#include "identify/identification_rig.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::identify {
namespace {

// Rods that form parallelograms with the carrying frame: it cannot roll or pitch.
bool parallel_equal_rods(const rig::RigGeometry& g) {
  const auto dir = [&](const rig::RodGeometry& r) { return (g.reference_point + r.lower - r.upper).normalized(); };
  for (const auto& r : g.rods) {
    if ((dir(r) - dir(g.rods.front())).norm() > 1e-6 || std::abs(r.length - g.rods.front().length) > 1e-6) return false;
  }
  return true;
}

}  // namespace

double accuracy_score(const ErrorSummary& e, const AccuracyLimits& limits) {
  limits.validate();
  double worst = (std::abs(e.zG_mean_m) + 2 * e.zG_std_m) / limits.cog_height_m;
  for (size_t i = 0; i < 3; ++i) {
    worst = std::max(worst, (std::abs(e.moment_mean[i]) + 2 * e.moment_std[i]) / limits.moment_relative);
  }
  worst = std::max(worst, e.product_max / limits.product_of_largest);
  return std::max(worst, e.cog_in_plane_max_m / limits.cog_in_plane_m);
}

rig::Verdict predicted_verdict(const ErrorSummary& e, const AccuracyLimits& limits) {
  const double score = accuracy_score(e, limits);
  return score <= 1.0 ? rig::Verdict::rigid_safe : score <= 2.0 ? rig::Verdict::marginal : rig::Verdict::use_flexible;
}

Prediction predict_identification_error(const rig::RigModel& model, const rig::CheckResult& r,
                                        const VirtualStudyOptions& o) {
  const rig::RigSystem truth(model);
  const IdentificationRig rigid = identification_rig(model, IdentificationAlgorithm::rigid);
  const IdentificationRig flexible = identification_rig(model, IdentificationAlgorithm::flexible);
  const VirtualStudy s = virtual_identification(truth, &rigid, &flexible, o);
  Prediction p;
  p.sets = o.sets;
  p.histories = o.histories;
  p.duration_s = o.duration_s;
  p.combined = r.verdict;
  if (!s.rigid->observable) {
    p.unobservable = s.rigid->unobservable;
    p.note = "the virtual measurement cannot identify every parameter (" + s.rigid->message + "). ";
    if (parallel_equal_rods(model.geometry)) {
      p.note += "The rods are parallel and of equal length: the carrying frame only translates and yaws, so roll "
                "and pitch are not excited; inclined rods would excite them. ";
    }
    p.note += "The verdict rests on the frequency ratio alone.";
    return p;
  }
  p.rigid = summarize_errors(s.rigid->found, s.truth);
  p.verdict = predicted_verdict(*p.rigid);
  if (p.verdict != rig::Verdict::rigid_safe && s.flexible->observable) {
    p.flexible = summarize_errors(s.flexible->found, s.truth);
    p.from_flexibility = summarize_errors(s.rigid->found, s.flexible->found);
    // Flexibility is to blame only where modelling it helps: when the
    // flexible algorithm misses the accuracy as well, noise and excitation
    // limit the identification and the ratio decides.
    if (accuracy_score(*p.flexible) > 1.0) {
      p.verdict = rig::Verdict::rigid_safe;
      p.note = "both algorithms miss the rig's accuracy on this virtual measurement: noise and excitation limit "
               "the identification (longer records, larger swings, inclined rods), not flexibility";
    }
  }
  p.combined = rig::worse(r.verdict, p.verdict);
  return p;
}

}  // namespace rigflex::identify
