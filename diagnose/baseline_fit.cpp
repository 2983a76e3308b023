#include "diagnose/baseline_fit.hpp"

#include <algorithm>
#include <cmath>

#include "diagnose/period_allowance.hpp"

namespace rigflex::diagnose {
namespace {

// (Named apart from diagnosis.cpp's helpers: the unity build compiles both in one unit.)
void report_stage(const DiagnosisOptions& options, const std::string& s) {
  if (options.progress) options.progress(s);
}

// Every candidate is scored by what it gains over the baseline: what the
// baseline leaves unconverged a candidate would gain as if it were its
// effect. The baseline's fits are cheap beside the catalogue's, so they
// relinearize while a linearization gains more than 1 %.
DiagnosisOptions tight(const DiagnosisOptions& options) {
  DiagnosisOptions t = options;
  t.relinearize_gain = std::min(options.relinearize_gain, DiagnosisOptions::kBaselineRelinearizeGain);
  return t;
}

// The body's fit from `start` (zero offsets), the states with it.
FitOutcome fit_body(Fitter& fit, const ResponseModel& base, const FitPoint& start, const DiagnosisOptions& options,
                    std::vector<Eigen::MatrixXd>& Js, std::vector<Eigen::MatrixXd>& Jbody) {
  Js = fit.state_jacobians(base, start.states, start.r);
  report_stage(options, "fitting the body's mass properties with the swing states");
  Jbody = fit.parameter_jacobians(nullptr, start.theta, start.states, start.r);
  return fit_nonlinear(fit, nullptr, start, Js, Jbody, tight(options));
}

// The residual's size and statistics at the fit `at`.
void residual_statistics(const FitPoint& at, const std::vector<const BandTarget*>& targets, Diagnosis& d) {
  d.residual = at.data;
  d.samples = 0;
  for (const auto& x : at.r) d.samples += static_cast<double>(x.size());
  d.independence = 0;
  for (const auto* t : targets) d.independence += t->band.independence() / static_cast<double>(targets.size());
  d.noise_ratio = at.data / d.samples;
}

}  // namespace

Baseline fit_baseline(Fitter& fit, const rig::RigModel& model, const ResponseModel& base,
                      const std::vector<const BandTarget*>& targets, const std::vector<SwingState>& states,
                      const DiagnosisOptions& options, Diagnosis& d) {
  const int H = fit.histories();
  Baseline b;
  b.initial_states = states;
  report_stage(options, "fitting the swing states to the whole records");
  Fitter plain(model, base, targets, BodyParameters{}, options.threads);
  const FitPoint first = evaluate(plain, nullptr, Eigen::VectorXd(), states);
  const std::vector<Eigen::MatrixXd> none(static_cast<size_t>(H));
  const FitOutcome s =
      fit_nonlinear(plain, nullptr, first, plain.state_jacobians(base, states, first.r), none, tight(options));
  b.start = evaluate(fit, nullptr, Eigen::VectorXd::Zero(fit.body_size()), s.at.states);
  FitOutcome o = fit_body(fit, base, b.start, options, b.Js, b.Jbody);
  b.at = std::move(o.at);
  b.schur_inverse = o.schur_inverse;
  residual_statistics(b.at, targets, d);
  b.dof = d.independence * (d.samples - (6.0 * H + fit.body_size()) / d.independence);
  return b;
}

// Fitted values with their standard deviations from the last linearization
// (parameters [first, first + specs.size()) of theta): the noise-weighted
// residual has unit variance per sample at the noise, the band's samples are
// correlated (1 / independence), and a misfit left over scales it up.
std::vector<FittedParameter> fitted_values(const std::vector<CandidateParameter>& specs, int first, const FitPoint& at,
                                           const Eigen::MatrixXd& schur_inverse, int fitted, const Diagnosis& d) {
  const int H = static_cast<int>(at.states.size());
  const double variance = std::max(1.0, at.data / std::max(d.samples - 6.0 * H - fitted, 1.0)) / d.independence;
  std::vector<FittedParameter> out;
  for (size_t i = 0; i < specs.size(); ++i) {
    const int k = first + static_cast<int>(i);
    FittedParameter fp;
    fp.name = specs[i].name;
    fp.unit = specs[i].unit;
    fp.value = at.theta(k);
    fp.std = specs[i].probe * std::sqrt(std::max(variance * schur_inverse(k, k), 0.0));
    fp.low = specs[i].low;
    fp.high = specs[i].high;
    fp.plausible = fp.value >= fp.low - 3 * fp.std && fp.value <= fp.high + 3 * fp.std;
    out.push_back(fp);
  }
  return out;
}

std::vector<FittedParameter> body_values(const Fitter& fit, const FitPoint& at, const Eigen::MatrixXd& schur_inverse,
                                         const Diagnosis& d) {
  auto out = fitted_values(fit.body().parameters, 0, at, schur_inverse, static_cast<int>(at.theta.size()), d);
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].prior_std = fit.body().sigma(static_cast<Eigen::Index>(i));
    out[i].plausible = true;  // the body has no physical range here: see `off`
    out[i].off = std::abs(out[i].value) > DiagnosisOptions::kOffSigmas * out[i].prior_std;
  }
  return out;
}

std::optional<ModelParameterFit> fit_model_parameters(const ResponseModel& base,
                                                      const std::vector<HistoryComparison>& histories,
                                                      const ModelParameterFitOptions& options) {
  if (histories.empty()) throw std::invalid_argument("fit_model_parameters needs at least one history");
  const rig::RigModel& model = base.system.model();
  DiagnosisOptions o;
  o.compare = options.compare;
  o.threads = options.threads;
  o.progress = options.progress;
  o.validate();
  std::vector<const BandTarget*> targets;
  std::vector<SwingState> states;
  for (const auto& h : histories) {
    targets.push_back(&h.target);
    states.push_back(h.fit.state);
  }
  Fitter fit(model, base, targets, body_parameters(model), options.threads);
  if (fit.body_size() == 0) return std::nullopt;
  // From compare's states (each fitted to its record's first seconds): the
  // body's fit refits them with it, so diagnose's first fit of the states
  // alone to the whole records would only cost time here.
  const FitPoint start = evaluate(fit, nullptr, Eigen::VectorXd::Zero(fit.body_size()), states);
  std::vector<Eigen::MatrixXd> Js, Jbody;
  const FitOutcome f = fit_body(fit, base, start, o, Js, Jbody);
  Diagnosis d;
  residual_statistics(f.at, targets, d);
  ModelParameterFit out;
  out.noise_ratio_as_stated = start.data / d.samples;
  out.noise_ratio = d.noise_ratio;
  out.parameters = body_values(fit, f.at, f.schur_inverse, d);
  for (const auto& p : out.parameters) {
    if (p.off) out.off.push_back(p);
  }
  // Far above the noise the offsets measure the model's missing physics, not
  // the body (diagnose's body_credible): the rig file's model is kept.
  const double gate = gate_ratio(o, period_error_residual(targets, o.period_tolerance) / d.samples);
  out.credible = f.at.data <= gate * d.samples;
  out.model = out.credible ? model_with(model, fit.body(), f.at.theta) : model;
  return out;
}

}  // namespace rigflex::diagnose
