#pragma once
// The fit of the model as the rig file states it, before any candidate
// effect: the swing states to the whole records, then the body's mass
// properties (and the model parameters whose uncertainty the rig file
// states, diagnose/body_parameters.hpp) with them. diagnose scores every
// candidate against it; compare reports it as the model's own parameters
// refitted (fit_model_parameters).
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "diagnose/diagnosis.hpp"
#include "diagnose/joint_fit.hpp"

namespace rigflex::diagnose {

// The baseline: the model as it is, the body refitted (`at`); and where
// every candidate's fit starts: the swing states refitted to the whole
// records with the body as the rig file gives it (`start`), and the
// Jacobians there, shared. Candidates start from the rig file's body, not
// from the baseline's: a model that misses an effect by far more than the
// noise pulls the body to wherever it absorbs most of the effect, a start
// from which the effect's own fit may not recover.
struct Baseline {
  std::vector<SwingState> initial_states;  // compare's, where a continuation fit starts
  FitPoint start;                          // theta: zero body offsets
  std::vector<Eigen::MatrixXd> Js, Jbody;  // at `start`
  FitPoint at;                             // theta: the body's fitted offsets
  Eigen::MatrixXd schur_inverse;
  double dof = 0;  // the F test's residual degrees of freedom before any effect parameter
};

// The baseline fits (states alone, then states and body). Sets the
// diagnosis' residual, sample count, independence and noise ratio.
Baseline fit_baseline(Fitter& fit, const rig::RigModel& model, const ResponseModel& base,
                      const std::vector<const BandTarget*>& targets, const std::vector<SwingState>& states,
                      const DiagnosisOptions& options, Diagnosis& d);

// Fitted values with their standard deviations from the last linearization
// (parameters [first, first + specs.size()) of theta).
std::vector<FittedParameter> fitted_values(const std::vector<CandidateParameter>& specs, int first, const FitPoint& at,
                                           const Eigen::MatrixXd& schur_inverse, int fitted, const Diagnosis& d);
// The body's (model parameters') offsets, each against its stated standard
// deviation: `off` beyond DiagnosisOptions::kOffSigmas of it.
std::vector<FittedParameter> body_values(const Fitter& fit, const FitPoint& at, const Eigen::MatrixXd& schur_inverse,
                                         const Diagnosis& d);

// compare's refit of the model's own parameters: the body and whatever the
// rig file states an uncertainty for, with the swing states, priors as in
// diagnose. Where the fit reaches the noise (within
// DiagnosisOptions::noise_excess) the offsets are credible and `model` has
// them; above it they would absorb a missing effect (run diagnose), and
// `model` is the rig file's.
struct ModelParameterFit {
  std::vector<FittedParameter> parameters;  // offsets from the rig file's values
  std::vector<FittedParameter> off;         // of those, beyond kOffSigmas of the stated std
  double noise_ratio_as_stated = 0;         // residual / noise with compare's swing states, the rig file's values
  double noise_ratio = 0;                   // with the parameters refitted too
  bool credible = false;
  rig::RigModel model;
};

struct ModelParameterFitOptions {
  CompareOptions compare;
  int threads = 0;
  std::function<void(const std::string&)> progress;
};

// `histories`: compare's result per history of `base`. None where the rig
// file states no uncertainty (body_parameters is empty): nothing to refit.
std::optional<ModelParameterFit> fit_model_parameters(const ResponseModel& base,
                                                      const std::vector<HistoryComparison>& histories,
                                                      const ModelParameterFitOptions& options);

}  // namespace rigflex::diagnose
