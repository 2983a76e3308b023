#pragma once
// The fit every diagnose step makes: each history's swing state, the body's
// mass properties (diagnose/body_parameters.hpp, with their priors) and a
// candidate effect's parameters, to the noise-weighted swing-band residuals
// of all records at once (diagnose/history_comparison.hpp). Gauss-Newton on
// the nonlinear model: sensitivities by finite differences of simulations,
// the states eliminated history by history (Schur complement), the priors
// as pseudo-observations; steps re-simulated until the objective (residual
// plus prior) falls - damped (Levenberg-Marquardt) with the body among the
// parameters, halved without it; chord steps on one linearization, then a
// new one while that gains.
#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "diagnose/body_parameters.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/effect_candidates.hpp"
#include "diagnose/history_comparison.hpp"

namespace rigflex::diagnose {

using Residuals = std::vector<Eigen::VectorXd>;
double sum_squares(const Residuals& r);

// The rig being diagnosed and the records, as functions of the parameters
// theta = [body offsets, candidate parameters].
class Fitter {
 public:
  Fitter(const rig::RigModel& model, const ResponseModel& base, std::vector<const BandTarget*> targets,
         BodyParameters body, int threads);

  // Residuals over the first `seconds` of every record only.
  void set_horizon(double seconds);
  bool horizon_covers_all() const;
  int histories() const { return static_cast<int>(targets_.size()); }
  const BodyParameters& body() const { return body_; }
  int body_size() const { return body_.size(); }
  int size(const EffectCandidate* c) const;     // body + candidate parameters
  Eigen::VectorXd probes(const EffectCandidate* c) const;
  // The priors' weight against the noise-weighted residual. At the noise a
  // record's band samples carry `independence` of a sample's information
  // each; a model that misses the data by more than the noise (a residual
  // of `misfit` x the noise) is a model error that the body must not absorb
  // beyond what the data, at that level, justify: the likelihood's variance
  // is the residual's, estimated from the records (the prior weighs
  // max(1, misfit) / independence).
  void set_misfit(double misfit) { prior_scale_ = std::max(1.0, misfit) / independence_; }
  double misfit_of(const Residuals& r) const;  // residual / noise expectation
  double prior_cost(const Eigen::VectorXd& theta) const;  // weighted sum of (offset / sigma)^2 over the body
  Eigen::VectorXd prior_inverse_sigma(const EffectCandidate* c) const;  // weighted; 0 for effect parameters

  Residuals residuals(const ResponseModel& m, const std::vector<SwingState>& s) const;
  // d(model)/d(state) per history (the residual's negative), forward differences.
  std::vector<Eigen::MatrixXd> state_jacobians(const ResponseModel& m, const std::vector<SwingState>& s,
                                               const Residuals& r0) const;
  // d(model)/d(theta_k) for k >= `from`, one probed model per parameter.
  std::vector<Eigen::MatrixXd> parameter_jacobians(const EffectCandidate* c, const Eigen::VectorXd& theta,
                                                   const std::vector<SwingState>& s, const Residuals& r0,
                                                   int from = 0) const;
  rig::RigModel with_parameters(const EffectCandidate* c, const Eigen::VectorXd& theta) const;

 private:
  const rig::RigModel& model_;
  const ResponseModel& base_;
  std::vector<const BandTarget*> targets_;
  BodyParameters body_;
  int threads_;
  std::vector<Eigen::Index> rows_;
  double independence_ = 1, prior_scale_ = 1;
};

// Where a fit stands: parameters, states, residuals.
struct FitPoint {
  Eigen::VectorXd theta;
  std::vector<SwingState> states;
  Residuals r;
  double data = 0;  // noise-weighted sum of squares
  double cost = 0;  // data + prior: the objective
};

struct FitOutcome {
  FitPoint at;
  double first_predicted = 0;       // residual the first linearized step predicted
  Eigen::MatrixXd schur_inverse;    // of the last linearization (scaled parameters)
  int steps = 0, linearizations = 1;
  std::string note;
};

// Evaluates theta and the states: residuals, data and objective.
FitPoint evaluate(const Fitter& fit, const EffectCandidate* c, Eigen::VectorXd theta, std::vector<SwingState> states);

// From `start` with the Jacobians at it (Jt: one matrix per history, a
// column per parameter of theta). The priors' weight follows the misfit,
// set at the start and at each new linearization.
FitOutcome fit_nonlinear(Fitter& fit, const EffectCandidate* c, FitPoint start, std::vector<Eigen::MatrixXd> Js,
                         std::vector<Eigen::MatrixXd> Jt, const DiagnosisOptions& options);

// The same fit by continuation over the record's length, from theta = 0 and
// the given states.
FitOutcome fit_by_continuation(Fitter& fit, const EffectCandidate* c, const std::vector<SwingState>& states,
                               const DiagnosisOptions& options);

}  // namespace rigflex::diagnose
