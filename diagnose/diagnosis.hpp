#pragma once
// Which physical effect is the model missing? For every effect of the
// catalogue (diagnose/effect_candidates.hpp) that the model does not contain,
// its parameters are fitted to the measurements together with every
// history's swing state and the body's CoG and inertia (with the priors the
// rig file states, diagnose/body_parameters.hpp), by Gauss-Newton on the
// noise-weighted swing-band residuals (diagnose/joint_fit.hpp). The baseline
// is the same fit without an effect; the fits of the significant effects
// that come near the best one are taken on to convergence from several
// starts (`contender_span`). Each effect is then scored by the share
// of the objective it explains, re-simulated, not predicted by the
// linearization. The body's fitted offsets beyond kOffSigmas of their
// stated uncertainty are reported as "model parameter off".
//
// Significance: an effect is reported as significant only when all hold:
//  - the model misses more than the noise and a simulator's numerics: the
//    baseline's noise-weighted residual exceeds what noise alone gives by
//    `noise_excess` (x 4 by default, see there) and by what a period error
//    of `period_tolerance` leaves in the records (Diagnosis::noise_gate);
//  - the F test of the effect's improvement, with the sample count reduced to
//    the band's independent samples, has a p-value below `significance`;
//  - it explains at least `min_explained` of the residual and
//    `min_excess_share` of the part above the noise.
// Ranking: by the share explained; of two effects that explain about the
// same (the richer one's extra improvement fails the F test at 1e-3), the
// one with fewer parameters first (a rod length error also fits as a
// vertical joint position error).
// Look-alikes: every other significant effect is tested against the missing
// one by Vuong's test for non-nested models (diagnose/fit_discrimination.hpp);
// one the records cannot tell from it at `discrimination` is named beside
// it, with the measurement that shows each directly.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "diagnose/history_comparison.hpp"
#include "diagnose/residual_analysis.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::diagnose {

struct DiagnosisOptions {
  CompareOptions compare;
  int refinements = 4;             // chord iterations per linearization
  int relinearizations = 2;        // new linearizations while they gain > relinearize_gain
  double relinearize_gain = 0.10;  // share of the objective (diagnose/joint_fit.cpp); the baseline: at most 1 %
  static constexpr double kBaselineRelinearizeGain = 0.01;
  // An effect that explains at least the threshold's share but less than
  // the ceiling's is fitted again by continuation over the record's length
  // (diagnosis.cpp), the better fit kept.
  double continuation_threshold = 0.05, continuation_ceiling = 0.9;
  // Contenders: the significant effects whose residual lies within
  // contender_span x the best one's. Before the ranking their fits are
  // taken on - from where they stand, by continuation over the records'
  // length, and from every other contender's body and swing states - while
  // a linearization gains more than contender_gain, up to
  // contender_relinearizations: two effects of similar reach (the fixed and
  // the carrying frame) must be ranked by where their fits end, not by how
  // far the first budget carried each (diagnosis.cpp).
  double contender_span = 100.0;
  double contender_gain = 0.01;
  int contender_relinearizations = 12;
  // A contender whose fit's residual is at most this x the noise
  // expectation is converged already (the model's own records give
  // 0.92-0.95 x): the data have nothing left for it to explain. 0: every
  // contender is taken on.
  double contender_settled = 1.0;
  // Restarts: where even the best contender's fit stays above
  // contender_settled, each contender whose residual lies within
  // restart_span x the best's is started again from its fit with one of
  // its effect's parameters set to zero at a time (the body back at the rig
  // file's values, the swing states refitted to each start as compare fits
  // them); the start closest to the records is taken on to convergence.
  // An effect's parameter trades against the body along curved valleys (a
  // plate's vertical compliance against the CoG height, its rocking
  // compliance against the roll and pitch inertia) whose local minima hold
  // a fit above the noise that a start on the valley's other side leaves
  // (diagnosis.cpp). 0: no restarts.
  double restart_span = 2.0;
  double significance = 1e-6;      // p-value of the F test
  double min_explained = 0.10;     // share of the baseline residual
  double min_excess_share = 0.20;  // share of the residual above the noise
  // Baseline residual / noise expectation - 1. Calibrated on control data:
  // the model's own records give 0.92-0.95 x the noise; records of the same
  // model integrated by CVODE's BDF2 (another simulator, each with a period
  // error near 1e-5) give 2.35 x, which the band's small noise shows as a
  // rod length error of some micrometres. The floor of the gate; in noise
  // units a simulator's numerics grow with the sample rate and a quieter
  // logger, so the gate also takes period_tolerance's allowance.
  double noise_excess = 3.0;
  // A relative error of the swing's period that the records' simulator may
  // have (diagnose/period_allowance.hpp): the gate is the larger of
  // noise_excess and what such an error leaves in the records at hand.
  // CVODE's BDF at its default tolerance leaves about 1.1e-5 (the clean
  // control at 1000 Hz: 6.6 x the noise, where 1e-5 leaves 5.5 x); 1.5e-5
  // keeps a margin of 1.4 on it, the margin noise_excess keeps at 500 Hz
  // (BDF's records there: 2.55 x, the gate 4 x). A pendulum of 1.5 m
  // changes its period that much with 0.05 mm more length: no rod is
  // measured that well.
  double period_tolerance = 1.5e-5;
  // Two significant effects are told apart when Vuong's test rejects "both
  // fit equally well" at this level (two-sided); otherwise both are named.
  double discrimination = 0.01;
  // Fit the candidates even where the model as it is reaches the noise
  // (the baseline within noise_excess of it). None can be significant there
  // - the test needs a residual above the noise to explain - so by default
  // they are not fitted: a clean record set is judged in the baseline's
  // time, not the catalogue's (the clean control: 87 -> 3 s).
  bool rank_at_noise = false;
  std::vector<std::string> effects;  // only these (empty: every effect the model lacks)
  // Effects the chain accepts at most (1: the missing effect alone).
  int max_effects = 3;
  int threads = 0;  // 0: the hardware's
  std::function<void(const std::string&)> progress;
  // A fitted model parameter is "off" beyond this many of its stated
  // standard deviations: 3 keeps a user's honest statement from being
  // flagged in more than 0.3 % of the cases per parameter.
  static constexpr double kOffSigmas = 3.0;
  void validate() const;  // std::invalid_argument naming the field
};

struct FittedParameter {
  std::string name, unit;
  double value = 0, std = 0;
  double low = 0, high = 0;  // plausible range
  bool plausible = true;
  // Model parameters (the body's): the offset from the rig file's value,
  // the standard deviation the rig file states for it, and whether the
  // offset lies beyond kOffSigmas of those: "model parameter off".
  double prior_std = 0;
  bool off = false;
};

struct EffectFit {
  std::string effect;
  std::vector<FittedParameter> parameters;
  double explained_fraction = 0;         // of the baseline residual, re-simulated
  double linear_explained_fraction = 0;  // as the linearization predicted
  double residual = 0;                   // noise-weighted sum of squares after the fit
  double f_statistic = 0, p_value = 1;
  bool significant = false, plausible = true;
  int refinements = 0;
  std::string rig_block;  // YAML under `effects:` with the fitted values; empty: no effect
  std::string advice;
  std::string evidence;  // a measurement that shows the effect directly
  // Vuong's test of this fit against the missing effect's (the first-ranked
  // effect's when none is): a p-value above DiagnosisOptions::discrimination
  // says the records cannot tell the two apart.
  double versus_first_p = 1;
  std::string note;                // why a refinement stopped, if it did
  std::vector<SwingState> states;  // refitted swing states per history
  // The body's offsets refitted with the effect; empty unless that fit
  // reaches the noise (`body_credible`, see diagnosis.cpp's score): above
  // it they measure the model's remaining error, not the body, and the
  // effect's values are those fitted with the rig file's body.
  std::vector<FittedParameter> body;
  bool body_credible = false;
};

// One step of the chain: the model with the effects accepted so far, all
// of them refitted together with the body and the swing states.
struct ChainStep {
  std::string effect;                       // added at this step
  double residual = 0;                      // noise-weighted sum of squares with it
  double noise_ratio = 0;                   // residual / samples
  double p_value = 1;                       // its F test against the step before
  std::vector<FittedParameter> parameters;  // every accepted effect's ("<effect>.<name>" for the earlier ones)
  std::string rig_block;                    // YAML under `effects:` adding them all
  std::vector<FittedParameter> body;        // as EffectFit::body
  bool body_credible = false;
  std::vector<EffectFit> ranking;  // tested at this step, on top of the steps before (the first: none)
};

struct Diagnosis {
  std::vector<HistoryComparison> baseline;  // compare's result per history
  ResidualAnalysis baseline_analysis;       // where the starting model fails (spectra, trend, decay)
  double residual = 0;                      // baseline noise-weighted sum of squares (states refitted)
  double samples = 0;                       // residual terms (band samples x channels)
  double independence = 1;                  // independent share of the band samples
  double noise_ratio = 0;                   // residual / samples: 1 = at the noise
  // What a period error of DiagnosisOptions::period_tolerance leaves, per
  // sample (the records' simulator's numerics), and the gate: at or below
  // noise_gate x the noise the model reaches the noise and those numerics.
  double numerics_ratio = 0, noise_gate = 0;
  std::vector<std::string> present;         // effects the model has (not tested)
  std::vector<EffectFit> ranking;           // best first
  std::optional<std::string> missing_effect;
  // The missing effect, then each further effect found significant with the
  // ones before it in the model (and refitted): empty when none is missing.
  std::vector<ChainStep> chain;
  // Tested on top of the whole chain, none significant; empty where the
  // chain stopped because its model reached the noise (or max_effects).
  std::vector<EffectFit> after_chain;
  std::string chain_note;  // why the chain stopped above the noise, where it did without testing further
  std::string ranking_note;  // why no candidate was fitted, where none was (DiagnosisOptions::rank_at_noise)
  std::vector<std::string> indistinguishable;  // significant effects the records cannot tell from it
  // The body's offsets fitted with the missing effect (or, with none, with
  // the model as it is), and those beyond what the rig file states; empty
  // where that model stays far above the noise (EffectFit::body_credible).
  std::vector<FittedParameter> body, parameters_off;
  std::string summary;  // one line: the verdict
};

// The residual / noise at or below which a model reaches the noise and a
// simulator's numerics: 1 + max(noise_excess, numerics_ratio).
double gate_ratio(const DiagnosisOptions& options, double numerics_ratio);

// How a fitted parameter's value is shown: lengths in mm, a dimensionless
// one (a gain) without a unit. `suffix` is " mm", " kg m^2" or "".
struct ShownUnit {
  double scale = 1;
  std::string suffix;
};
ShownUnit shown_unit(const std::string& unit);

// A model parameter that is off, in words: "cog.z +8.1 mm (stated +-2)".
std::string describe_off(const FittedParameter& p);

Diagnosis diagnose(const rig::RigModel& model, const std::vector<const rig::Record*>& records,
                   const std::vector<std::string>& sources, const DiagnosisOptions& options);

}  // namespace rigflex::diagnose
