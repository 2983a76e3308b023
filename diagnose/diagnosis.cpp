#include "diagnose/diagnosis.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "diagnose/effect_candidates.hpp"
#include "rig/effect_kinds.hpp"
#include "rig/equilibrium.hpp"
#include "identify/identification_kinematics.hpp"
#include "rig/parallel_for.hpp"

namespace rigflex::diagnose {

void DiagnosisOptions::validate() const {
  compare.validate();
  if (refinements < 0) throw std::invalid_argument("refinements: must be >= 0");
  if (relinearizations < 0) throw std::invalid_argument("relinearizations: must be >= 0");
  if (!(continuation_threshold >= 0 && continuation_threshold <= continuation_ceiling)) {
    throw std::invalid_argument("continuation_threshold: must lie in [0, continuation_ceiling]");
  }
  if (!(significance > 0 && significance < 1)) throw std::invalid_argument("significance: must lie in (0, 1)");
  if (!(min_explained >= 0 && min_explained < 1)) throw std::invalid_argument("min_explained: must lie in [0, 1)");
  if (!(min_excess_share >= 0 && min_excess_share <= 1)) {
    throw std::invalid_argument("min_excess_share: must lie in [0, 1]");
  }
  if (!(noise_excess >= 0)) throw std::invalid_argument("noise_excess: must be >= 0");
  for (const auto& e : effects) {
    if (!rig::find_effect_kind(e)) throw std::invalid_argument("effects: unknown effect '" + e + "'");
  }
}

namespace {

using Residuals = std::vector<Eigen::VectorXd>;

double sum_squares(const Residuals& r) {
  double s = 0;
  for (const auto& x : r) s += x.squaredNorm();
  return s;
}

double lowest_swing_hz(const ResponseModel& m) {
  for (const auto& mode : m.linearization.modes) {
    if (mode.kind == rig::RigModeKind::swing) return mode.frequency_hz;
  }
  return 0.0;
}

SwingState state_steps(const ResponseModel& m) {
  double L = 0;
  for (const auto& r : m.system.assembly().geometry.rods) L += r.length / m.system.rods();
  const double w = 2.0 * std::numbers::pi * std::max(lowest_swing_hz(m), 0.1);
  SwingState s;
  s << L, L, 1.0, L * w, L * w, w;
  return 5e-6 * s;
}

class Fitter {
 public:
  Fitter(const rig::RigModel& model, const ResponseModel& base, std::vector<const BandTarget*> targets, int threads)
      : model_(model), base_(base), targets_(std::move(targets)), threads_(threads) {
    set_horizon(INFINITY);
  }

  // Residuals over the first `seconds` of every record only.
  void set_horizon(double seconds) {
    rows_.clear();
    for (const auto* t : targets_) rows_.push_back(std::isfinite(seconds) ? t->rows_within(seconds) : -1);
  }
  bool horizon_covers_all() const {
    for (size_t j = 0; j < targets_.size(); ++j) {
      if (rows_[j] >= 0 && rows_[j] < static_cast<Eigen::Index>(targets_[j]->at.size())) return false;
    }
    return true;
  }

  int histories() const { return static_cast<int>(targets_.size()); }

  Residuals residuals(const ResponseModel& m, const std::vector<SwingState>& s) const {
    Residuals r(targets_.size());
    rig::parallel_for(histories(), threads_, [&](int j) { r[j] = band_residual(m, s[j], *targets_[j], rows_[j]); });
    return r;
  }

  // d(model)/d(state) per history (the residual's negative), forward differences.
  std::vector<Eigen::MatrixXd> state_jacobians(const ResponseModel& m, const std::vector<SwingState>& s,
                                               const Residuals& r0) const {
    const SwingState h = state_steps(base_);
    std::vector<Eigen::MatrixXd> J(targets_.size());
    for (size_t j = 0; j < targets_.size(); ++j) J[j].resize(r0[j].size(), 6);
    rig::parallel_for(6 * histories(), threads_, [&](int task) {
      const int j = task / 6, k = task % 6;
      SwingState sp = s[j];
      sp(k) += h(k);
      J[j].col(k) = (r0[j] - band_residual(m, sp, *targets_[j], rows_[j])) / h(k);
    });
    return J;
  }

  // Parameter sensitivities of a candidate at theta: one model per parameter, probed.
  std::vector<Eigen::MatrixXd> parameter_jacobians(const EffectCandidate& c, const Eigen::VectorXd& theta,
                                                   const std::vector<SwingState>& s, const Residuals& r0) const {
    const int p = static_cast<int>(c.parameters.size());
    std::vector<std::unique_ptr<ResponseModel>> probes(p);
    rig::parallel_for(p, threads_, [&](int k) {
      Eigen::VectorXd th = theta;
      th(k) += c.parameters[k].probe;
      probes[k] = std::make_unique<ResponseModel>(with_effect(c, th));
    });
    std::vector<Eigen::MatrixXd> J(targets_.size());
    for (size_t j = 0; j < targets_.size(); ++j) J[j].resize(r0[j].size(), p);
    rig::parallel_for(p * histories(), threads_, [&](int task) {
      const int j = task / p, k = task % p;
      J[j].col(k) = (r0[j] - band_residual(*probes[k], s[j], *targets_[j], rows_[j])) / c.parameters[k].probe;
    });
    return J;
  }

  rig::RigModel with_effect(const EffectCandidate* c, const Eigen::VectorXd& theta) const {
    if (!c) return model_;
    return with_effect(*c, theta);
  }
  rig::RigModel with_effect(const EffectCandidate& c, const Eigen::VectorXd& theta) const {
    rig::RigModel m = model_;
    if (auto e = c.make(theta)) m.effects.push_back(std::move(e));
    return m;
  }

 private:
  const rig::RigModel& model_;
  const ResponseModel& base_;
  std::vector<const BandTarget*> targets_;
  int threads_;
  std::vector<Eigen::Index> rows_;
};

// The linearized least-squares step for the states of every history and the
// shared parameters, the states eliminated history by history (Schur
// complement). Parameters are scaled by their probes; directions the data
// cannot fix are left out by a pseudo-inverse.
struct Step {
  std::vector<SwingState> ds;
  Eigen::VectorXd dtheta;
  Eigen::MatrixXd schur_inverse;  // scaled parameters
  double predicted = 0;           // predicted sum of squares after the step
};

Step gauss_newton(const std::vector<Eigen::MatrixXd>& Js, const std::vector<Eigen::MatrixXd>& Jt,
                  const Residuals& r, const Eigen::VectorXd& scale) {
  const Eigen::Index p = scale.size();
  const size_t H = Js.size();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(p);
  std::vector<Eigen::LDLT<Eigen::Matrix<double, 6, 6>>> A(H);
  std::vector<Eigen::MatrixXd> B(H);
  std::vector<SwingState> a(H);
  for (size_t j = 0; j < H; ++j) {
    Eigen::Matrix<double, 6, 6> Aj = Js[j].transpose() * Js[j];
    Aj.diagonal() += Eigen::Matrix<double, 6, 1>::Constant(1e-12 * Aj.diagonal().maxCoeff());
    A[j].compute(Aj);
    a[j] = Js[j].transpose() * r[j];
    if (p > 0) {
      const Eigen::MatrixXd Jtj = Jt[j] * scale.asDiagonal();
      B[j] = Js[j].transpose() * Jtj;
      S += Jtj.transpose() * Jtj - B[j].transpose() * A[j].solve(B[j]);
      b += Jtj.transpose() * r[j] - B[j].transpose() * A[j].solve(a[j]);
    }
  }
  Step st;
  st.dtheta = Eigen::VectorXd::Zero(p);
  st.schur_inverse = Eigen::MatrixXd::Zero(p, p);
  if (p > 0) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    Eigen::VectorXd inv = Eigen::VectorXd::Zero(p);
    for (Eigen::Index i = 0; i < p; ++i) {
      if (sv(i) > 1e-10 * sv(0)) inv(i) = 1.0 / sv(i);
    }
    st.schur_inverse = svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose();
    st.dtheta = st.schur_inverse * b;
  }
  st.ds.resize(H);
  st.predicted = 0;
  for (size_t j = 0; j < H; ++j) {
    Eigen::VectorXd rhs = a[j];
    if (p > 0) rhs -= B[j] * st.dtheta;
    st.ds[j] = A[j].solve(rhs);
    Eigen::VectorXd rj = r[j] - Js[j] * st.ds[j];
    if (p > 0) rj -= Jt[j] * (scale.asDiagonal() * st.dtheta);
    st.predicted += rj.squaredNorm();
  }
  st.dtheta = scale.asDiagonal() * st.dtheta;  // back to parameter units
  return st;
}

// Where a fit stands: parameters, states, residuals.
struct FitPoint {
  Eigen::VectorXd theta;
  std::vector<SwingState> states;
  Residuals r;
  double cost = 0;
};

struct FitOutcome {
  FitPoint at;
  double first_predicted = 0;       // sum of squares the first linearized step predicted
  Eigen::MatrixXd schur_inverse;    // of the last linearization (scaled parameters)
  int steps = 0, linearizations = 1;
  std::string note;
};

// Gauss-Newton with step halving on the nonlinear model: chord steps on the
// Jacobians of the last linearization while they make progress, then a new
// linearization, while that still gains more than 1 % (a large effect moves
// the swing's phase by radians over a record, beyond one linearization).
FitOutcome fit_nonlinear(Fitter& fit, const EffectCandidate* c, FitPoint start,
                         std::vector<Eigen::MatrixXd> Js, std::vector<Eigen::MatrixXd> Jt,
                         const DiagnosisOptions& options) {
  const int p = c ? static_cast<int>(c->parameters.size()) : 0;
  const int H = fit.histories();
  Eigen::VectorXd scale(p);
  for (int k = 0; k < p; ++k) scale(k) = c->parameters[k].probe;
  FitOutcome out;
  out.at = std::move(start);
  bool first = true;
  for (int lin = 0; lin <= options.relinearizations; ++lin) {
    const double cost_before = out.at.cost;
    bool converged = false;
    for (int it = 0; it <= options.refinements && !converged; ++it) {
      const Step st = gauss_newton(Js, Jt, out.at.r, scale);
      if (it == 0) out.schur_inverse = st.schur_inverse;
      if (first) out.first_predicted = st.predicted, first = false;
      bool accepted = false;
      for (double lambda = 1.0; lambda >= 0.125 && !accepted; lambda *= 0.5) {
        FitPoint trial;
        trial.theta = out.at.theta + lambda * st.dtheta;
        for (int k = 0; k < p; ++k) {
          if (c->parameters[k].non_negative) trial.theta(k) = std::max(trial.theta(k), 0.0);
        }
        trial.states = out.at.states;
        for (int j = 0; j < H; ++j) trial.states[j] += lambda * st.ds[j];
        try {
          const ResponseModel m(fit.with_effect(c, trial.theta));
          trial.r = fit.residuals(m, trial.states);
          trial.cost = sum_squares(trial.r);
        } catch (const std::exception& x) {
          out.note = std::string("a step gave a rig that could not be simulated: ") + x.what();
          continue;
        }
        if (trial.cost < out.at.cost) {
          converged = (out.at.cost - trial.cost) < 1e-4 * out.at.cost;
          out.at = std::move(trial);
          accepted = true;
          ++out.steps;
        }
      }
      if (!accepted) break;
    }
    const bool gained = out.at.cost < 0.99 * cost_before;
    if (!gained || lin == options.relinearizations) break;
    // Linearize again where the fit now stands.
    try {
      const ResponseModel m(fit.with_effect(c, out.at.theta));
      Js = fit.state_jacobians(m, out.at.states, out.at.r);
      if (c) Jt = fit.parameter_jacobians(*c, out.at.theta, out.at.states, out.at.r);
      ++out.linearizations;
    } catch (const std::exception& x) {
      out.note = std::string("a linearization failed: ") + x.what();
      break;
    }
  }
  return out;
}

// The same fit by continuation over the record's length: from the first
// 2 x fit_window seconds, doubling, to the whole record, each stage started
// where the last ended. A large effect shifts the swing's phase by radians
// over a whole record but little over its first seconds, so each stage
// starts inside the next one's basin where one linearization over the
// whole record may not.
FitOutcome fit_by_continuation(Fitter& fit, const EffectCandidate* c, const std::vector<SwingState>& states,
                               const DiagnosisOptions& options) {
  const int p = c ? static_cast<int>(c->parameters.size()) : 0;
  FitPoint pt;
  pt.theta = Eigen::VectorXd::Zero(p);
  pt.states = states;
  FitOutcome o;
  for (double horizon = 2.0 * options.compare.fit_window_s;; horizon *= 2.0) {
    fit.set_horizon(horizon);
    const bool last = fit.horizon_covers_all();
    if (last) fit.set_horizon(INFINITY);
    const ResponseModel m(fit.with_effect(c, pt.theta));
    pt.r = fit.residuals(m, pt.states);
    pt.cost = sum_squares(pt.r);
    auto Js = fit.state_jacobians(m, pt.states, pt.r);
    std::vector<Eigen::MatrixXd> Jt(static_cast<size_t>(fit.histories()));
    if (c) Jt = fit.parameter_jacobians(*c, pt.theta, pt.states, pt.r);
    DiagnosisOptions stage = options;
    if (!last) stage.relinearizations = 0;
    o = fit_nonlinear(fit, c, pt, Js, Jt, stage);
    pt = o.at;
    if (last) break;
  }
  return o;
}

double f_test_p_value(double improvement, double dof1, double residual, double dof2) {
  if (dof1 <= 0 || dof2 <= 1 || residual <= 0) return 1.0;
  if (improvement <= 0) return 1.0;
  const double F = (improvement / dof1) / (residual / dof2);
  const boost::math::fisher_f_distribution<double> dist(dof1, dof2);
  return boost::math::cdf(boost::math::complement(dist, F));
}

// Where every candidate's fit starts: the baseline, the states refitted to
// the whole record (no parameters), and its one linearization, shared.
struct Baseline {
  std::vector<SwingState> initial_states;  // compare's, where a continuation fit starts
  std::vector<SwingState> states;
  Residuals r;
  double rss = 0;
  std::vector<Eigen::MatrixXd> Js;
  double dof = 0;  // the F test's residual degrees of freedom before any parameter
};

void progress(const DiagnosisOptions& options, const std::string& s) {
  if (options.progress) options.progress(s);
}

// compare's result per history and where the starting model fails.
void compare_histories(const ResponseModel& base, const std::vector<const rig::Record*>& records,
                       const std::vector<std::string>& sources, const DiagnosisOptions& options, Diagnosis& d) {
  const int H = static_cast<int>(records.size());
  d.baseline.resize(records.size());
  progress(options, "fitting the swing states of " + std::to_string(H) + " histories");
  rig::parallel_for(H, options.threads, [&](int j) {
    try {
      d.baseline[j] = compare_history(base, *records[j], j < static_cast<int>(sources.size()) ? sources[j] : "",
                                      options.compare);
    } catch (rig::RecordError& e) {
      e.set_history(j);
      throw;
    }
  });
  d.baseline_analysis = analyse_residuals(base, d.baseline);
}

// The baseline fit, and the diagnosis' residual, sample count and noise ratio.
Baseline fit_baseline(Fitter& fit, const ResponseModel& base, const std::vector<const BandTarget*>& targets,
                      const std::vector<SwingState>& states, const DiagnosisOptions& options, Diagnosis& d) {
  const int H = fit.histories();
  Baseline b;
  b.initial_states = states;
  FitPoint start;
  start.states = states;
  start.r = fit.residuals(base, states);
  start.cost = sum_squares(start.r);
  progress(options, "state sensitivities");
  const std::vector<Eigen::MatrixXd> none(static_cast<size_t>(H));
  const FitOutcome o = fit_nonlinear(fit, nullptr, start, fit.state_jacobians(base, states, start.r), none, options);
  b.states = o.at.states;
  b.r = o.at.r;
  b.rss = o.at.cost;
  b.Js = fit.state_jacobians(base, b.states, b.r);
  d.residual = b.rss;
  d.samples = 0;
  for (const auto& x : b.r) d.samples += static_cast<double>(x.size());
  d.independence = 0;
  for (const auto* t : targets) d.independence += t->band.independence() / static_cast<double>(targets.size());
  d.noise_ratio = d.residual / d.samples;
  b.dof = d.independence * (d.samples - 6.0 * H / d.independence);
  return b;
}

// The catalogue's effects the model lacks, of those asked for.
std::vector<EffectCandidate> candidates_to_test(const ResponseModel& base, const std::vector<std::string>& present,
                                                const DiagnosisOptions& options) {
  const CandidateContext context = candidate_context(base.system, lowest_swing_hz(base));
  std::vector<EffectCandidate> candidates;
  for (auto& c : effect_candidates(context)) {
    const bool has = std::find(present.begin(), present.end(), c.effect) != present.end();
    const bool wanted = options.effects.empty() ||
                        std::find(options.effects.begin(), options.effects.end(), c.effect) != options.effects.end();
    if (!has && wanted) candidates.push_back(std::move(c));
  }
  return candidates;
}

// The candidate's fit from the baseline; one that explains a relevant share
// is fitted again by continuation, the better fit kept.
FitOutcome fit_candidate(Fitter& fit, const EffectCandidate& c, const Baseline& b, const DiagnosisOptions& options) {
  FitPoint from;
  from.theta = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(c.parameters.size()));
  from.states = b.states;
  from.r = b.r;
  from.cost = b.rss;
  FitOutcome o = fit_nonlinear(fit, &c, from, b.Js, fit.parameter_jacobians(c, from.theta, b.states, b.r), options);
  const double direct = b.rss > 0 ? (b.rss - o.at.cost) / b.rss : 0.0;
  if (direct >= options.continuation_threshold && direct < options.continuation_ceiling) {
    try {
      FitOutcome oc = fit_by_continuation(fit, &c, b.initial_states, options);
      oc.first_predicted = o.first_predicted;
      if (oc.at.cost < o.at.cost) o = std::move(oc);
    } catch (const std::exception& x) {
      o.note = std::string("the continuation fit failed: ") + x.what();
    }
    fit.set_horizon(INFINITY);
  }
  return o;
}

// The fitted parameters with their standard deviations from the last
// linearization: the noise-weighted residual has unit variance per sample
// at the noise, the band's samples are correlated (1 / independence), and a
// misfit left over scales it up.
std::vector<FittedParameter> fitted_parameters(const EffectCandidate& c, const FitOutcome& o, const Diagnosis& d) {
  const int p = static_cast<int>(c.parameters.size());
  const int H = static_cast<int>(d.baseline.size());
  const double variance = std::max(1.0, o.at.cost / std::max(d.samples - 6.0 * H - p, 1.0)) / d.independence;
  std::vector<FittedParameter> out;
  for (int k = 0; k < p; ++k) {
    FittedParameter fp;
    fp.name = c.parameters[k].name;
    fp.unit = c.parameters[k].unit;
    fp.value = o.at.theta(k);
    fp.std = c.parameters[k].probe * std::sqrt(std::max(variance * o.schur_inverse(k, k), 0.0));
    fp.low = c.parameters[k].low;
    fp.high = c.parameters[k].high;
    fp.plausible = fp.value >= fp.low - 3 * fp.std && fp.value <= fp.high + 3 * fp.std;
    out.push_back(fp);
  }
  return out;
}

// The candidate's fit scored: share explained, F test, significance.
EffectFit score(const EffectCandidate& c, const FitOutcome& o, const Baseline& b, const Diagnosis& d,
                const DiagnosisOptions& options) {
  const int p = static_cast<int>(c.parameters.size());
  const double rss = b.rss, cost = o.at.cost;
  EffectFit ef;
  ef.effect = c.effect;
  ef.advice = c.advice;
  ef.linear_explained_fraction = rss > 0 ? std::max(0.0, (rss - o.first_predicted) / rss) : 0.0;
  ef.refinements = o.steps;
  ef.note = o.note;
  ef.residual = cost;
  ef.states = o.at.states;
  ef.explained_fraction = rss > 0 ? std::max(0.0, (rss - cost) / rss) : 0.0;
  ef.parameters = fitted_parameters(c, o, d);
  for (const auto& fp : ef.parameters) ef.plausible = ef.plausible && fp.plausible;
  const double dof = b.dof - p;
  const double improvement = (rss - cost) * d.independence;
  ef.p_value = f_test_p_value(improvement, p, cost * d.independence, dof);
  ef.f_statistic = dof > 0 && cost > 0 ? (improvement / p) / (cost * d.independence / dof) : 0.0;
  const double excess = std::max(rss - d.samples, 0.0);
  ef.significant = d.noise_ratio > 1.0 + options.noise_excess && ef.p_value < options.significance &&
                   ef.explained_fraction >= options.min_explained &&
                   (rss - cost) >= options.min_excess_share * excess;
  if (c.make(o.at.theta)) ef.rig_block = c.rig_block(o.at.theta);  // none when the fit amounts to no effect
  return ef;
}

// By explained share; then a leaner effect that explains statistically as
// much goes before a richer neighbour.
void rank(std::vector<EffectFit>& ranking, const Diagnosis& d, double dof_base) {
  std::stable_sort(ranking.begin(), ranking.end(),
                   [](const EffectFit& a, const EffectFit& b) { return a.explained_fraction > b.explained_fraction; });
  for (size_t pass = 0; pass < ranking.size(); ++pass) {
    bool swapped = false;
    for (size_t i = 1; i < ranking.size(); ++i) {
      EffectFit& rich = ranking[i - 1];
      EffectFit& lean = ranking[i];
      const double extra = static_cast<double>(rich.parameters.size()) - static_cast<double>(lean.parameters.size());
      if (extra <= 0) continue;
      const double dof = dof_base - static_cast<double>(rich.parameters.size());
      const double pv =
          f_test_p_value((lean.residual - rich.residual) * d.independence, extra, rich.residual * d.independence, dof);
      if (pv > 1e-3) {
        std::swap(rich, lean);
        swapped = true;
      }
    }
    if (!swapped) break;
  }
}

// The first significant effect, and the one-line verdict.
void conclude(Diagnosis& d, const DiagnosisOptions& options) {
  for (const auto& e : d.ranking) {
    if (e.significant) {
      d.missing_effect = e.effect;
      break;
    }
  }
  if (d.missing_effect) {
    d.summary = "missing effect: " + *d.missing_effect;
  } else if (d.noise_ratio <= 1.0 + options.noise_excess) {
    d.summary = "no significant missing effect: the model matches the measurements to the noise (and the "
                "simulator's numerics)";
  } else {
    d.summary = "no significant missing effect: no effect of the catalogue explains the residual";
  }
}

}  // namespace

Diagnosis diagnose(const rig::RigModel& model, const std::vector<const rig::Record*>& records,
                   const std::vector<std::string>& sources, const DiagnosisOptions& options) {
  options.validate();
  if (records.empty()) throw std::invalid_argument("diagnose needs at least one history");
  const ResponseModel base(model);
  Diagnosis d;
  compare_histories(base, records, sources, options, d);
  std::vector<const BandTarget*> targets;
  std::vector<SwingState> states;
  for (const auto& h : d.baseline) {
    targets.push_back(&h.target);
    states.push_back(h.fit.state);
  }
  Fitter fit(model, base, targets, options.threads);
  const Baseline b = fit_baseline(fit, base, targets, states, options, d);
  for (const auto& e : model.effects) d.present.push_back(e->name());
  for (const EffectCandidate& c : candidates_to_test(base, d.present, options)) {
    progress(options, "fitting " + c.effect);
    d.ranking.push_back(score(c, fit_candidate(fit, c, b, options), b, d, options));
  }
  rank(d.ranking, d, b.dof);
  conclude(d, options);
  return d;
}

}  // namespace rigflex::diagnose
