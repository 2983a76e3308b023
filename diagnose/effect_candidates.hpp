#pragma once
// The catalogue's effects as `rigflex diagnose` fits them: each kind's fit
// entry in rig/effect_kinds.hpp (a small set of parameters, probes for the
// finite-difference sensitivities, plausible ranges, what to add to the
// model to capture it properly) made concrete for the rig being diagnosed,
// with the rig-file block that adds the fitted effect. Why these
// parameterizations: docs/compare.md.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rig/effect.hpp"
#include "rig/effect_kinds.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::diagnose {

// What the parameterizations are scaled by: the rig being diagnosed.
using CandidateContext = rig::FitContext;
CandidateContext candidate_context(const rig::RigSystem& rig, double lowest_swing_hz);

using CandidateParameter = rig::FitParameter;

struct EffectCandidate {
  std::string effect;                               // the spec's name
  std::vector<CandidateParameter> parameters;
  // The effect with these parameter values (non-negative ones clamped at 0);
  // nullptr when the values amount to no effect (a compliance of zero).
  std::function<std::shared_ptr<const rig::Effect>(const Eigen::VectorXd&)> make;
  // Rig-file block (YAML, under `effects:`) that adds the effect with the
  // values theta: the kind's parameters written by rig::effect_yaml, with
  // their `uncertainty` propagated from the fit's standard deviations `std`
  // (rig::fitted_uncertainty; none where `std` is empty).
  std::function<std::string(const Eigen::VectorXd& theta, const Eigen::VectorXd& std)> rig_block;
  std::string advice;                               // what to add to capture it properly
  std::string evidence;                             // a measurement that shows it directly
  bool stand_in = false;                            // rig::EffectFitting::stand_in
};

// Every effect of the catalogue, in the spec's order.
std::vector<EffectCandidate> effect_candidates(const CandidateContext& context);

}  // namespace rigflex::diagnose
