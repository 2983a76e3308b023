#include "rig/design_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rigflex::rig {
namespace {

struct Frequencies {
  double swing_max = 0;
  std::optional<double> f1;
  std::optional<double> ratio() const {
    if (!f1 || swing_max <= 0) return std::nullopt;
    return *f1 / swing_max;
  }
};

Frequencies frequencies_of(const Linearization& lin) {
  Frequencies f;
  for (const RigMode& m : lin.modes) {
    if (m.kind == RigModeKind::swing) f.swing_max = std::max(f.swing_max, m.frequency_hz);
    if (m.kind == RigModeKind::deformation && !f.f1) f.f1 = m.frequency_hz;
  }
  return f;
}

Frequencies scaled(const RigModel& model, Component c, double s) {
  const RigSystem rig(model, c == Component::fixed_frame ? s : 1.0, c == Component::rods ? s : 1.0,
                      c == Component::carrying_frame ? s : 1.0);
  return frequencies_of(linearize(rig));
}

// Bisection on log(s) for ratio(s) = target over [1, 1e4], for a rig whose
// ratio misses the target: the ratio grows with the stiffness of the
// component that dominates f1 until another component or the swing takes
// over. A rig that finds no equilibrium at s counts as ratio 0.
StiffnessAdvice advise(const RigModel& model, Component c, double target) {
  StiffnessAdvice a;
  a.component = c;
  constexpr double hi_bound = 1e4;
  const auto ratio_at = [&](double s) {
    try {
      return scaled(model, c, s).ratio().value_or(HUGE_VAL);
    } catch (const NoEquilibrium&) {
      return 0.0;
    }
  };
  a.ratio_limit = ratio_at(hi_bound);
  if (a.ratio_limit < target) {
    a.message = std::string("stiffening the ") + to_string(c) + " alone cannot reach the target: ratio " +
                std::to_string(a.ratio_limit) + " at 1e4 times its stiffness; stiffen the other components too";
    return a;
  }
  // Called only when ratio(1) < target: the factor lies in (1, 1e4].
  double lo = 0.0, hi = std::log(hi_bound);
  for (int it = 0; it < 40 && hi - lo > 1e-4; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ratio_at(std::exp(mid)) < target ? lo : hi) = mid;
  }
  a.factor = std::exp(hi);
  char text[200];
  std::snprintf(text, sizeof text, "make the %s %.3g times stiffer to bring the ratio to %g", to_string(c), *a.factor,
                target);
  a.message = text;
  return a;
}

}  // namespace

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::rigid_safe: return "rigid identification safe";
    case Verdict::marginal: return "marginal";
    case Verdict::use_flexible: return "use the flexible algorithm";
  }
  return "?";
}

const char* to_string(Component c) {
  switch (c) {
    case Component::fixed_frame: return "fixed_frame";
    case Component::rods: return "rods";
    case Component::carrying_frame: return "carrying_frame";
  }
  return "?";
}

void CheckOptions::validate() const {
  if (!(marginal_ratio > 0 && target_ratio > marginal_ratio)) {
    throw std::invalid_argument("check: need 0 < marginal_ratio < target_ratio");
  }
}

CheckResult design_check(const RigModel& model, const CheckOptions& options) {
  options.validate();
  CheckResult r;
  const RigSystem rig(model);
  r.linearization = linearize(rig);
  const RigMode* first = nullptr;
  for (const RigMode& m : r.linearization.modes) {
    if (m.kind == RigModeKind::swing) r.swing_frequencies_hz.push_back(m.frequency_hz);
    if (m.kind == RigModeKind::deformation && !first) first = &m;
  }
  const Frequencies f = frequencies_of(r.linearization);
  r.first_deformation_frequency_hz = f.f1;
  r.ratio = f.ratio();
  if (r.ratio) {
    r.verdict = *r.ratio >= options.target_ratio  ? Verdict::rigid_safe
                : *r.ratio >= options.marginal_ratio ? Verdict::marginal
                                                     : Verdict::use_flexible;
  }
  if (first) {
    const double total = first->strain.total();
    r.share_fixed_frame = first->strain.fixed_frame / total;
    r.share_rods = first->strain.rods / total;
    r.share_carrying_frame = first->strain.carrying_frame / total;
    double best = r.share_fixed_frame;
    if (r.share_rods > best) r.dominant = Component::rods, best = r.share_rods;
    if (r.share_carrying_frame > best) r.dominant = Component::carrying_frame;
    if (r.ratio && *r.ratio < options.target_ratio) r.advice = advise(model, r.dominant, options.target_ratio);
  }
  return r;
}

Verdict worse(Verdict a, Verdict b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

}  // namespace rigflex::rig
