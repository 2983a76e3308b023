#include "identify/predicted_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

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

template <typename... A>
std::string format(const char* f, A... a) {
  char text[400];
  std::snprintf(text, sizeof text, f, a...);
  return text;
}

std::string ratio_text(const rig::CheckResult& r) {
  return r.ratio ? format("f1 / highest swing = %.3g", *r.ratio) : std::string("no deformation mode");
}

// The error that flexibility causes, quasi-static at the swing frequencies,
// grows with the dominant component's compliance: stiffening it by the
// error's factor over the accuracy brings that error to the accuracy. An
// estimate, stated as one.
rig::StiffnessAdvice error_advice(rig::Component c, double score) {
  rig::StiffnessAdvice a;
  a.component = c;
  a.factor = score;
  a.message = format("make the %s about %.3g times stiffer: the predicted error that its flexibility causes then falls "
                     "to the rig's accuracy (an estimate: that error grows with the compliance)",
                     rig::to_string(c), score);
  return a;
}

CheckConclusion verdict_of(const rig::CheckResult& check, const std::optional<Prediction>& p) {
  CheckConclusion c;
  c.verdict = check.verdict;
  if (!p) {
    c.reason = "from the frequency ratio alone (" + ratio_text(check) + "); no predicted error was asked for";
  } else if (!p->rigid) {
    c.reason = "from the frequency ratio alone (" + ratio_text(check) + "): the virtual measurement could not "
               "predict the error";
  } else {
    c.verdict = rig::worse(check.verdict, p->verdict);
    if (p->verdict == check.verdict) {
      c.reason = "the frequency ratio (" + ratio_text(check) + ") and the predicted error agree";
    } else if (c.verdict == p->verdict) {
      c.reason = "the predicted error decides: the frequency ratio (" + ratio_text(check) + ") alone would say '" +
                 rig::to_string(check.verdict) + "', but flexibility costs more than the rig's accuracy";
    } else {
      c.reason = "the frequency ratio decides (" + ratio_text(check) + "): the predicted error alone would say '" +
                 rig::to_string(p->verdict) + "'";
    }
  }
  return c;
}

}  // namespace

CheckConclusion conclude_check(const rig::CheckResult& check, const std::optional<Prediction>& p,
                               const AccuracyLimits& limits) {
  CheckConclusion c = verdict_of(check, p);
  if (check.advice) {
    c.advice = check.advice;
    c.advice_reason = "frequency ratio";
  }
  if (p && p->from_flexibility && p->verdict != rig::Verdict::rigid_safe) {
    const double score = accuracy_score(*p->from_flexibility, limits);
    // The stricter need wins; a ratio that stiffening cannot reach stays the advice.
    const bool stricter = !check.advice || (check.advice->factor && score > *check.advice->factor);
    if (score > 1.0 && stricter) {
      c.advice = error_advice(check.dominant, score);
      c.advice_reason = "predicted error";
    }
  }
  return c;
}

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

Prediction predict_identification_error(const rig::RigModel& model, const VirtualStudyOptions& o) {
  const rig::RigSystem truth(model);
  const IdentificationRig rigid = identification_rig(model, IdentificationAlgorithm::rigid);
  const IdentificationRig flexible = identification_rig(model, IdentificationAlgorithm::flexible);
  const VirtualStudy s = virtual_identification(truth, &rigid, &flexible, o);
  Prediction p;
  p.sets = o.sets;
  p.histories = o.histories;
  p.duration_s = o.duration_s;
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
  return p;
}

}  // namespace rigflex::identify
