#include "diagnose/body_parameters.hpp"

#include <algorithm>
#include <array>

#include "rig/effects.hpp"

namespace rigflex::diagnose {

namespace {
const std::array<const char*, 10> kNames{"cog_x", "cog_y", "cog_z", "Jxx", "Jyy",
                                         "Jzz",   "Jxy",   "Jxz",   "Jyz", "rods.stiffness"};
constexpr int kRodStiffness = 9;
}  // namespace

BodyParameters body_parameters(const rig::RigModel& model) {
  const auto Jstd = model.body_uncertainty.inertia_std(model.body);
  std::array<double, 10> sigma{};
  for (int k = 0; k < 3; ++k) sigma[k] = model.body_uncertainty.cog(k);
  for (int k = 0; k < 6; ++k) sigma[3 + k] = Jstd[k];
  if (!model.rods.stiffness.empty()) sigma[kRodStiffness] = 100.0 * model.rods.stiffness_uncertainty;  // %
  // Probes: small against the prior (the responses are smooth in the mass
  // properties) yet far above the simulator's round-off: 0.2 mm of CoG and
  // 0.2 % of the mean principal moment move the swing-band forces by
  // several times their noise on the test rigs. The rods' stiffness moves
  // the swing band only through the static stretch (the body hangs lower)
  // and the rods' bounce modes far above it: a 1 % probe.
  const double moment = model.body.inertia.trace() / 3.0;
  BodyParameters p;
  std::vector<double> s;
  for (int k = 0; k < 10; ++k) {
    if (!(sigma[k] > 0)) continue;
    p.components.push_back(k);
    rig::FitParameter f;
    f.name = kNames[k];
    f.unit = k < 3 ? "m" : k < kRodStiffness ? "kg m^2" : "%";
    f.probe = k < 3 ? 2e-4 : k < kRodStiffness ? 2e-3 * moment : 1.0;
    f.low = -3 * sigma[k];
    f.high = 3 * sigma[k];
    p.parameters.push_back(f);
    s.push_back(sigma[k]);
  }
  // An effect's parameters: probes a tenth of the stated deviation (the
  // effects' responses are smooth in their parameters; the deviation is the
  // scale on which the user expects the value to be wrong).
  int item = 0;
  for (const auto& u : model.effect_uncertainty) {
    for (const auto& it : u.items) {
      p.components.push_back(BodyParameters::kEffectItems + item++);
      rig::FitParameter f;
      f.name = "effects." + u.effect + "." + it.name();
      f.unit = it.unit;
      f.probe = 0.1 * it.sigma;
      f.low = -3 * it.sigma;
      f.high = 3 * it.sigma;
      p.parameters.push_back(f);
      s.push_back(it.sigma);
    }
  }
  p.sigma = Eigen::Map<const Eigen::VectorXd>(s.data(), static_cast<Eigen::Index>(s.size()));
  return p;
}

namespace {

// A stiffness's factor from its fitted offset in %. A fit far past the
// prior may ask for a stiffness below nothing: the factor is kept positive
// (a rig can then still be simulated, and the prior and the data push back).
double stiffness_factor(double offset_percent) { return std::max(1.0 + offset_percent / 100.0, 1e-3); }

// Each effect with stated uncertainties rebuilt from its parameters plus
// their offsets, in its place among the model's effects (a frame: scaled). An effect a fit
// moves outside what its kind accepts throws, as any rig the fit cannot
// simulate (the fits treat that step as failed).
void refit_effects(rig::RigModel& m, const BodyParameters& p, const Eigen::VectorXd& delta) {
  int first = 0;
  for (const auto& u : m.effect_uncertainty) {
    const int n = static_cast<int>(u.items.size());
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    bool moved = false;
    for (int i = 0; i < p.size(); ++i) {
      const int item = p.components[i] - BodyParameters::kEffectItems - first;
      if (item >= 0 && item < n) {
        d(item) = delta(i);
        moved = moved || delta(i) != 0.0;
      }
    }
    first += n;
    if (!moved) continue;
    if (u.frame_stiffness) {
      for (auto& e : m.effects) {
        if (u.effect == e->name()) e = rig::stiffened(*e, stiffness_factor(d(0)));
      }
      continue;
    }
    const rig::EffectKind& kind = *rig::find_effect_kind(u.effect);
    auto rebuilt = kind.parse(rig::with_offsets(u, d), rig::parse_context(m, u.effect));
    for (auto& e : m.effects) {
      if (u.effect == e->name()) e = rebuilt;
    }
  }
}

}  // namespace

fe::MassProperties body_with(const fe::MassProperties& body, const BodyParameters& p, const Eigen::VectorXd& delta) {
  fe::MassProperties out = body;
  std::array<double, 6> J = rig::inertia_components(body.inertia);
  for (int i = 0; i < p.size(); ++i) {
    const int k = p.components[i];
    if (k < 3) {
      out.cog(k) += delta(i);
    } else if (k < kRodStiffness) {
      J[k - 3] += delta(i);
    }
  }
  out.inertia = rig::inertia_tensor(J);
  return out;
}

rig::RigModel model_with(const rig::RigModel& model, const BodyParameters& p, const Eigen::VectorXd& delta) {
  rig::RigModel out = model;
  out.body = body_with(model.body, p, delta);
  for (int i = 0; i < p.size(); ++i) {
    if (p.components[i] != kRodStiffness) continue;
    const double factor = stiffness_factor(delta(i));
    for (double& k : out.rods.stiffness) k *= factor;
  }
  refit_effects(out, p, delta);
  return out;
}

}  // namespace rigflex::diagnose
