#include "diagnose/diagnosis.hpp"

#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>

#include "diagnose/baseline_fit.hpp"
#include "diagnose/effect_candidates.hpp"
#include "diagnose/effect_chain.hpp"
#include "diagnose/fit_discrimination.hpp"
#include "diagnose/joint_fit.hpp"
#include "diagnose/period_allowance.hpp"
#include "identify/identification_kinematics.hpp"
#include "rig/effect_kinds.hpp"
#include "rig/effects.hpp"
#include "rig/equilibrium.hpp"
#include "rig/parallel_for.hpp"

namespace rigflex::diagnose {

void DiagnosisOptions::validate() const {
  compare.validate();
  if (refinements < 0) throw std::invalid_argument("refinements: must be >= 0");
  if (relinearizations < 0) throw std::invalid_argument("relinearizations: must be >= 0");
  if (!(relinearize_gain >= 0 && relinearize_gain < 1))
    throw std::invalid_argument("relinearize_gain: must lie in [0, 1)");
  if (!(continuation_threshold >= 0 && continuation_threshold <= continuation_ceiling)) {
    throw std::invalid_argument("continuation_threshold: must lie in [0, continuation_ceiling]");
  }
  if (!(contender_span >= 1)) throw std::invalid_argument("contender_span: must be >= 1");
  if (!(contender_gain >= 0 && contender_gain < 1)) throw std::invalid_argument("contender_gain: must lie in [0, 1)");
  if (!(contender_settled >= 0)) throw std::invalid_argument("contender_settled: must be >= 0");
  if (!(restart_span == 0 || restart_span >= 1)) throw std::invalid_argument("restart_span: must be 0 or >= 1");
  if (contender_relinearizations < 0) throw std::invalid_argument("contender_relinearizations: must be >= 0");
  if (!(significance > 0 && significance < 1)) throw std::invalid_argument("significance: must lie in (0, 1)");
  if (!(min_explained >= 0 && min_explained < 1)) throw std::invalid_argument("min_explained: must lie in [0, 1)");
  if (!(min_excess_share >= 0 && min_excess_share <= 1)) {
    throw std::invalid_argument("min_excess_share: must lie in [0, 1]");
  }
  if (!(noise_excess >= 0)) throw std::invalid_argument("noise_excess: must be >= 0");
  if (!(period_tolerance >= 0 && period_tolerance < 1e-2)) {
    throw std::invalid_argument("period_tolerance: must lie in [0, 0.01)");
  }
  if (!(discrimination > 0 && discrimination < 1)) throw std::invalid_argument("discrimination: must lie in (0, 1)");
  if (max_effects < 1) throw std::invalid_argument("max_effects: must be >= 1");
  for (const auto& e : effects) {
    if (!rig::find_effect_kind(e)) throw std::invalid_argument("effects: unknown effect '" + e + "'");
  }
}

double gate_ratio(const DiagnosisOptions& options, double numerics_ratio) {
  return 1.0 + std::max(options.noise_excess, numerics_ratio);
}

namespace {

double f_test_p_value(double improvement, double dof1, double residual, double dof2) {
  if (dof1 <= 0 || dof2 <= 1 || residual <= 0) return 1.0;
  if (improvement <= 0) return 1.0;
  const double F = (improvement / dof1) / (residual / dof2);
  const boost::math::fisher_f_distribution<double> dist(dof1, dof2);
  return boost::math::cdf(boost::math::complement(dist, F));
}

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
      d.baseline[j] =
          compare_history(base, *records[j], j < static_cast<int>(sources.size()) ? sources[j] : "", options.compare);
    } catch (rig::RecordError& e) {
      e.set_history(j);
      throw;
    }
  });
  d.baseline_analysis = analyse_residuals(base, d.baseline);
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

// The objective of two fits compared at one prior weight (the lower
// misfit's: the priors weigh least where the data say most).
bool better_fit(Fitter& fit, const FitPoint& a, const FitPoint& b) {
  fit.set_misfit(std::min(fit.misfit_of(a.r), fit.misfit_of(b.r)));
  return a.data + fit.prior_cost(a.theta) < b.data + fit.prior_cost(b.theta);
}

// The candidate's fit in two ways, the better kept:
//  - direct: the body and the effect together from the baseline's start;
//    one that explains a relevant share is fitted again by continuation;
//  - staged: the effect with the body as the rig file gives it (`held`),
//    then the body freed from there. An effect's parameter and the body's
//    inertia can trade along a long valley (a carrying frame's rocking
//    compliance against roll and pitch inertia) that the direct fit may not
//    follow to its end; the staged fit starts at the body-held optimum, so
//    its objective can only fall below it.
struct CandidateFits {
  FitOutcome joint;                // the body refitted with the effect: the ranking's
  std::optional<FitOutcome> held;  // the body as the rig file gives it
};

// What a candidate's fit is scored against: the model before it (the
// baseline, or the chain's last step).
struct Reference {
  double residual = 0;      // noise-weighted sum of squares
  double dof = 0;           // the F test's residual degrees of freedom without the candidate
  int held_parameters = 0;  // of the candidate's parameters, those the reference fitted already
};

// A fit taken on from `pt` with a new linearization there.
FitOutcome refit_from(Fitter& fit, const EffectCandidate& c, const FitPoint& pt, const DiagnosisOptions& options) {
  const ResponseModel m(fit.with_parameters(&c, pt.theta));
  return fit_nonlinear(fit, &c, pt, fit.state_jacobians(m, pt.states, pt.r),
                       fit.parameter_jacobians(&c, pt.theta, pt.states, pt.r), options);
}

CandidateFits fit_candidate(Fitter& fit, Fitter& held, const EffectCandidate& c, const Baseline& b,
                            const DiagnosisOptions& options) {
  const int nb = fit.body_size(), n = fit.size(&c), p = n - nb;
  FitPoint from = b.start;
  from.theta = Eigen::VectorXd::Zero(n);
  const auto Je = fit.parameter_jacobians(&c, from.theta, from.states, from.r, nb);
  std::vector<Eigen::MatrixXd> Jt(b.Jbody.size());
  for (size_t j = 0; j < Jt.size(); ++j) {
    Jt[j].resize(Je[j].rows(), n);
    Jt[j] << b.Jbody[j], Je[j];
  }
  FitOutcome o = fit_nonlinear(fit, &c, from, b.Js, Jt, options);
  const double rss = b.at.data;
  const double direct = rss > 0 ? (rss - o.at.data) / rss : 0.0;
  if (direct >= options.continuation_threshold && direct < options.continuation_ceiling) {
    try {
      FitOutcome oc = fit_by_continuation(fit, &c, b.initial_states, options);
      oc.first_predicted = o.first_predicted;
      if (better_fit(fit, oc.at, o.at)) o = std::move(oc);
    } catch (const std::exception& x) {
      o.note = std::string("the continuation fit failed: ") + x.what();
    }
    fit.set_horizon(INFINITY);
  }
  if (nb == 0) return {o, std::nullopt};
  FitPoint held_start = b.start;
  held_start.theta = Eigen::VectorXd::Zero(p);
  const FitOutcome h = fit_nonlinear(held, &c, held_start, b.Js, Je, options);
  if (!(h.at.data < o.at.data + fit.prior_cost(o.at.theta))) return {o, h};  // the direct fit is already below it
  try {
    Eigen::VectorXd theta = Eigen::VectorXd::Zero(n);
    theta.tail(p) = h.at.theta;
    FitOutcome s = refit_from(fit, c, evaluate(fit, &c, theta, h.at.states), options);
    s.first_predicted = o.first_predicted;
    s.steps += h.steps;
    if (better_fit(fit, s.at, o.at)) o = std::move(s);
  } catch (const std::exception& x) {
    o.note = std::string("the staged fit failed: ") + x.what();
  }
  return {o, h};
}

Eigen::VectorXd standard_deviations(const std::vector<FittedParameter>& ps) {
  Eigen::VectorXd s(static_cast<Eigen::Index>(ps.size()));
  for (size_t i = 0; i < ps.size(); ++i) s(static_cast<Eigen::Index>(i)) = ps[i].std;
  return s;
}

// The candidate's fit scored: share explained, F test, significance.
// Ranked by the joint fit (the body refitted); its values - the effect's
// and the body's - are reported only where that fit reaches the noise
// (`body_credible`). A fit left far above the noise is a stand-in for
// physics the catalogue lacks (a frame's dynamics beyond its quasi-static
// compliance): the body's offsets then absorb part of that model error
// along the directions the data cannot separate from the effect (a CoG
// height against a vertical compliance), and the effect's values go with
// that wrong body. So there the values reported, and written to the
// effects file, are those fitted with the body the rig file gives.
EffectFit score(const Fitter& fit, const EffectCandidate& c, const CandidateFits& fits, const Reference& ref,
                const Diagnosis& d, const DiagnosisOptions& options) {
  const FitOutcome& o = fits.joint;
  const int p = static_cast<int>(c.parameters.size()), nb = fit.body_size();
  const int tested = p - ref.held_parameters;  // the candidate's own parameters
  // Scored on the data alone (the priors only keep the body where the data
  // cannot fix it): the reference's residual against the candidate's.
  const double rss = ref.residual, cost = o.at.data;
  EffectFit ef;
  ef.effect = c.effect;
  ef.advice = c.advice;
  ef.evidence = c.evidence;
  ef.linear_explained_fraction = rss > 0 ? std::max(0.0, (rss - o.first_predicted) / rss) : 0.0;
  ef.refinements = o.steps;
  ef.note = o.note;
  ef.residual = cost;
  ef.states = o.at.states;
  ef.explained_fraction = rss > 0 ? std::max(0.0, (rss - cost) / rss) : 0.0;
  ef.parameters = fitted_values(c.parameters, nb, o.at, o.schur_inverse, nb + p, d);
  for (const auto& fp : ef.parameters) ef.plausible = ef.plausible && fp.plausible;
  ef.body_credible = nb > 0 && cost <= d.noise_gate * d.samples;
  Eigen::VectorXd theta = o.at.theta.tail(p);
  if (ef.body_credible) {
    ef.body = body_values(fit, o.at, o.schur_inverse, d);
  } else if (fits.held) {
    ef.parameters = fitted_values(c.parameters, 0, fits.held->at, fits.held->schur_inverse, p, d);
    for (const auto& fp : ef.parameters) ef.plausible = ef.plausible && fp.plausible;
    theta = fits.held->at.theta;
  }
  const double dof = ref.dof - tested;
  const double improvement = (rss - cost) * d.independence;
  ef.p_value = f_test_p_value(improvement, tested, cost * d.independence, dof);
  ef.f_statistic = dof > 0 && cost > 0 ? (improvement / tested) / (cost * d.independence / dof) : 0.0;
  const double excess = std::max(rss - d.samples, 0.0);
  // An implausible fit is never the missing effect: the catalogue's effect
  // stretched beyond physics to mimic something else.
  ef.significant = rss > d.noise_gate * d.samples && ef.p_value < options.significance &&
                   ef.explained_fraction >= options.min_explained &&
                   (rss - cost) >= options.min_excess_share * excess && ef.plausible;
  // None when the fit amounts to no effect; with the values' uncertainty,
  // so that the effect, once added, is refitted like any stated value.
  if (c.make(theta)) {
    try {
      ef.rig_block = c.rig_block(theta, standard_deviations(ef.parameters));
    } catch (const rig::ParameterError& e) {
      // Values the rig reader would refuse: beyond physics, so never the
      // missing effect (a short rod's plausible box can reach past them),
      // and no file that compare --effects could not read.
      ef.plausible = false;
      ef.significant = false;
      ef.note += std::string(ef.note.empty() ? "" : "; ") + "no effects file: " + e.what();
    }
  }
  return ef;
}

// The fit budget of a fit taken on to convergence (contender_gain, contender_relinearizations).
DiagnosisOptions to_convergence(const DiagnosisOptions& options) {
  DiagnosisOptions deep = options;
  deep.relinearize_gain = options.contender_gain;
  deep.relinearizations = options.contender_relinearizations;
  return deep;
}

// A restart of candidate c at theta: the swing states refitted to every
// record as compare fits them for that model (a start's states from
// another fit leave it several times further from the records: measured
// on the carrying frame's acceptance case, its restarts ended at 1.29 x
// the noise from those, 1.03 x from these). None where the model cannot
// be simulated.
std::optional<FitPoint> restart_point(Fitter& fit, const EffectCandidate& c, Eigen::VectorXd theta,
                                      const std::vector<const rig::Record*>& records, const DiagnosisOptions& options) {
  try {
    const ResponseModel m(fit.with_parameters(&c, theta));
    std::vector<SwingState> states(records.size());
    rig::parallel_for(static_cast<int>(records.size()), options.threads,
                      [&](int j) { states[j] = compare_history(m, *records[j], "", options.compare).fit.state; });
    return evaluate(fit, &c, std::move(theta), std::move(states));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// DiagnosisOptions::restart_span: where the best contender's fit stays
// above contender_settled, each contender within restart_span of it is
// started again with one of its effect's parameters at zero at a time and
// the body at the rig file's values; the start whose refitted states lie
// closest to the records is taken on (`take_on` keeps it where it ends
// lower). Screening the starts by their residual costs one state fit per
// start (about 2 s on the trifilar's six records), a fit of each about
// 10-20 s; on the carrying frame's acceptance case the start residuals
// ranked the five starts' ends in the same order.
template <class TakeOn>
void restart_contenders(Fitter& fit, const std::vector<EffectCandidate>& candidates,
                        const std::vector<size_t>& contenders, const std::vector<const rig::Record*>& records,
                        const DiagnosisOptions& options, const Diagnosis& d, TakeOn take_on,
                        const std::vector<CandidateFits>& fits) {
  if (options.restart_span == 0 || contenders.empty()) return;
  double best = INFINITY;
  for (size_t k : contenders) best = std::min(best, fits[k].joint.at.data);
  if (best <= options.contender_settled * d.samples) return;
  const int nb = fit.body_size();
  for (size_t i = 0; i < contenders.size(); ++i) {
    const size_t k = contenders[i];
    const FitPoint& at = fits[k].joint.at;  // read before take_on replaces it
    if (at.data > options.restart_span * best) continue;
    const int p = static_cast<int>(candidates[k].parameters.size());
    progress(options, "restarting " + candidates[k].effect + " from " + std::to_string(p) + " starts (contender " +
                          std::to_string(i + 1) + " of " + std::to_string(contenders.size()) + ")");
    std::optional<FitPoint> chosen;
    for (int q = 0; q < p; ++q) {
      if (at.theta(nb + q) == 0) continue;
      Eigen::VectorXd theta = at.theta;
      theta.head(nb).setZero();
      theta(nb + q) = 0;
      std::optional<FitPoint> start = restart_point(fit, candidates[k], std::move(theta), records, options);
      if (start && (!chosen || start->data < chosen->data)) chosen = std::move(start);
    }
    if (chosen) take_on(k, *chosen);
  }
}

// The contenders' fits (DiagnosisOptions::contender_span) taken on until a
// linearization gains less than contender_gain, and scored again. Each is
// fitted again by continuation over the records' length, then taken on
// from the lower of that and the fit it had, then from every other
// contender's body and swing states with its own effect values; the lowest
// is kept. A large effect slips the swing's phase by cycles over a record,
// and a fit to the whole record can settle in a basin a cycle off (seen: a
// carrying frame at 6.7 x the noise, 1.02 x by continuation) or crawl up a
// long valley where the effect trades against the body's inertia and CoG
// height; a look-alike's fit (the fixed frame's) can carry the body to
// where the records put it (seeds 3-5 of bench_diagnosis_seeds' carrying
// frame: named only with these starts). `ranking` and `fits` are in the
// candidates' order.
void converge_contenders(Fitter& fit, const std::vector<EffectCandidate>& candidates, std::vector<CandidateFits>& fits,
                         const Baseline& b, const Reference& ref, const std::vector<const rig::Record*>& records,
                         const DiagnosisOptions& options, Diagnosis& d) {
  std::optional<size_t> best;
  for (size_t k = 0; k < d.ranking.size(); ++k) {
    if (d.ranking[k].significant && (!best || d.ranking[k].residual < d.ranking[*best].residual)) best = k;
  }
  if (!best) return;
  std::vector<size_t> contenders;
  for (size_t k = 0; k < d.ranking.size(); ++k) {
    if (d.ranking[k].significant && d.ranking[k].residual <= options.contender_span * d.ranking[*best].residual) {
      contenders.push_back(k);
    }
  }
  const DiagnosisOptions deep = to_convergence(options);
  // Another fit of contender k, kept where it ends below the fit so far.
  auto keep_better = [&](size_t k, FitOutcome more) {
    FitOutcome& o = fits[k].joint;
    if (!better_fit(fit, more.at, o.at)) return;
    more.first_predicted = o.first_predicted;
    more.steps += o.steps;
    o = std::move(more);
  };
  auto take_on = [&](size_t k, const FitPoint& start) {
    try {
      keep_better(k, refit_from(fit, candidates[k], start, deep));
    } catch (const std::exception& x) {
      fits[k].joint.note = std::string("converging the fit failed: ") + x.what();
    }
  };
  const std::string of = " of " + std::to_string(contenders.size()) + ")";
  // A fit at or below the noise expectation has nothing left that another
  // basin could explain beyond the noise itself: it is not taken on.
  auto settled = [&](size_t k) { return fits[k].joint.at.data <= options.contender_settled * d.samples; };
  for (size_t i = 0; i < contenders.size(); ++i) {
    const size_t k = contenders[i];
    if (settled(k)) continue;
    progress(options, "converging " + candidates[k].effect + " (contender " + std::to_string(i + 1) + of);
    try {
      FitOutcome oc = fit_by_continuation(fit, &candidates[k], b.initial_states, deep);
      fit.set_horizon(INFINITY);
      keep_better(k, std::move(oc));
    } catch (const std::exception& x) {
      fit.set_horizon(INFINITY);
      fits[k].joint.note = std::string("the continuation fit failed: ") + x.what();
    }
    take_on(k, fits[k].joint.at);
  }
  const int nb = fit.body_size();
  if (nb > 0 && contenders.size() > 1) {
    std::vector<FitPoint> ends;  // each contender's fit so far: the other ones' starts
    for (size_t k : contenders) ends.push_back(fits[k].joint.at);
    for (size_t i = 0; i < contenders.size(); ++i) {
      const size_t k = contenders[i];
      if (settled(k)) continue;
      progress(options, "converging " + candidates[k].effect + " from the other contenders' bodies (contender " +
                            std::to_string(i + 1) + of);
      for (size_t j = 0; j < contenders.size(); ++j) {
        if (j == i) continue;
        Eigen::VectorXd theta = fits[k].joint.at.theta;
        theta.head(nb) = ends[j].theta.head(nb);
        std::optional<FitPoint> start;
        try {
          start = evaluate(fit, &candidates[k], std::move(theta), ends[j].states);
        } catch (const std::exception&) {
          continue;  // a rig that cannot be simulated: no start there
        }
        take_on(k, *start);
      }
    }
  }
  restart_contenders(fit, candidates, contenders, records, options, d, take_on, fits);
  for (size_t k : contenders) d.ranking[k] = score(fit, candidates[k], fits[k], ref, d, options);
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

// The missing effect: the first significant one of the ranking.
const EffectFit* first_significant(const std::vector<EffectFit>& ranking) {
  const auto e = std::find_if(ranking.begin(), ranking.end(), [](const EffectFit& x) { return x.significant; });
  return e == ranking.end() ? nullptr : &*e;
}

// Each fit against the missing effect's (or the first-ranked's): Vuong's
// test on their band residuals.
void discriminate_against_first(Diagnosis& d, const std::map<std::string, FitPoint>& points,
                                const std::vector<const BandTarget*>& targets) {
  if (d.ranking.size() < 2) return;
  const EffectFit* significant = first_significant(d.ranking);
  const EffectFit* first = significant ? significant : &d.ranking.front();
  DiscriminationInput in;
  in.first = &points.at(first->effect).r;
  in.independence = d.independence;
  for (size_t j = 0; j < targets.size(); ++j) {
    in.rows.push_back((*in.first)[j].size() / std::max<Eigen::Index>(1, targets[j]->measured.cols()));
  }
  for (auto& e : d.ranking) {
    if (e.effect == first->effect) continue;
    in.second = &points.at(e.effect).r;
    in.parameter_difference = static_cast<double>(first->parameters.size()) - static_cast<double>(e.parameters.size());
    e.versus_first_p = discriminate(in).p_value;
  }
}

// A step of the chain: the effect it accepted, as its ranking scored it.
ChainStep chain_step(const EffectFit& e, const Diagnosis& d) {
  ChainStep st;
  st.effect = e.effect;
  st.residual = e.residual;
  st.noise_ratio = e.residual / d.samples;
  st.p_value = e.p_value;
  st.parameters = e.parameters;
  st.rig_block = e.rig_block;
  st.body = e.body;
  st.body_credible = e.body_credible;
  return st;
}

// The step's first significant effect - the one the chain accepts - taken
// on to convergence (as the first step's contenders are) and scored again:
// the chain's last step is the model diagnose writes, values and body
// together. Its start is the step before's fit, whose body had absorbed
// what it could of this effect; a fit stopped early leaves part of that
// in the body (seen: two hidden effects, the CoG height 2 mm off at 1.1 x
// the noise).
void converge_accepted(Fitter& fit, const std::vector<EffectCandidate>& candidates,
                       const std::vector<const EffectCandidate*>& accepted, const Reference& ref,
                       const DiagnosisOptions& options, Diagnosis& d, std::vector<EffectFit>& ranking,
                       std::map<std::string, FitPoint>& points) {
  const auto first = std::find_if(ranking.begin(), ranking.end(), [](const EffectFit& e) { return e.significant; });
  if (first == ranking.end()) return;
  const auto next = std::find_if(candidates.begin(), candidates.end(),
                                 [&](const EffectCandidate& x) { return x.effect == first->effect; });
  const EffectCandidate c = chained_candidate(accepted, &*next);
  progress(options, "the chain, step " + std::to_string(d.chain.size() + 1) + ": converging " + c.effect);
  FitPoint& at = points[first->effect];
  const DiagnosisOptions deep = to_convergence(options);
  try {
    CandidateFits fits{refit_from(fit, c, at, deep), std::nullopt};
    if (!better_fit(fit, fits.joint.at, at)) return;
    EffectFit e = score(fit, c, fits, ref, d, options);
    e.refinements += first->refinements;
    *first = std::move(e);
    at = std::move(fits.joint.at);
  } catch (const std::exception& x) {
    first->note = std::string("converging the fit failed: ") + x.what();
  }
}

// Every candidate not yet accepted, fitted on top of the accepted effects
// (their parameters refitted with it, the body and the states too, from
// where the last step ended) and scored against that step: Gauss-Newton
// from one shared linearization per step (no continuation or staged fits:
// the accepted effects already carry the model near the data).
std::vector<EffectFit> test_on_top(Fitter& fit, const std::vector<EffectCandidate>& candidates,
                                   const std::vector<const EffectCandidate*>& accepted, const FitPoint& point,
                                   const Baseline& b, const DiagnosisOptions& options, Diagnosis& d,
                                   std::map<std::string, FitPoint>& points) {
  const int nb = fit.body_size();
  const EffectCandidate held = chained_candidate(accepted, nullptr);
  const int held_parameters = static_cast<int>(held.parameters.size());
  const ResponseModel m(fit.with_parameters(&held, point.theta));
  const auto Js = fit.state_jacobians(m, point.states, point.r);
  const auto Jheld = fit.parameter_jacobians(&held, point.theta, point.states, point.r);
  const Reference ref{point.data, b.dof - held_parameters, held_parameters};
  std::string with;
  for (const auto* a : accepted) with += (with.empty() ? "" : ", ") + a->effect;
  std::vector<EffectFit> ranking;
  for (const EffectCandidate& next : candidates) {
    if (std::find(accepted.begin(), accepted.end(), &next) != accepted.end()) continue;
    progress(options,
             "the chain, step " + std::to_string(d.chain.size() + 1) + ": fitting " + next.effect + " with " + with);
    const EffectCandidate c = chained_candidate(accepted, &next);
    FitPoint from = point;
    from.theta = Eigen::VectorXd::Zero(fit.size(&c));
    from.theta.head(point.theta.size()) = point.theta;
    const auto Je = fit.parameter_jacobians(&c, from.theta, from.states, from.r, nb + held_parameters);
    std::vector<Eigen::MatrixXd> Jt(Je.size());
    for (size_t j = 0; j < Jt.size(); ++j) {
      Jt[j].resize(Je[j].rows(), Jheld[j].cols() + Je[j].cols());
      Jt[j] << Jheld[j], Je[j];
    }
    CandidateFits fits{fit_nonlinear(fit, &c, from, Js, Jt, options), std::nullopt};
    ranking.push_back(score(fit, c, fits, ref, d, options));
    points[next.effect] = std::move(fits.joint.at);
  }
  rank(ranking, d, b.dof);  // each fit's parameter count includes the accepted ones'
  converge_accepted(fit, candidates, accepted, ref, options, d, ranking, points);
  return ranking;
}

// After the missing effect, the next: while the model with the accepted
// effects still misses the records by more than the noise can (the same
// gate as the first step's), every other candidate is fitted on top of
// them and the first significant one of that ranking accepted. Not past a
// stand-in (a frame's joint compliance for its FE model) left above that
// gate: what it leaves is its own model error, and on the tutorial's
// records (examples/hidden-effect) encoder offsets and joint positions,
// fitted on top of the fixed frame's stand-in, took 80 % and 90 % of it.
void follow_chain(Fitter& fit, const std::vector<EffectCandidate>& candidates, const Baseline& b,
                  const std::map<std::string, FitPoint>& points, const DiagnosisOptions& options, Diagnosis& d) {
  const EffectFit* missing = first_significant(d.ranking);
  if (!missing) return;
  d.chain.push_back(chain_step(*missing, d));
  auto candidate = [&](const std::string& name) {
    return &*std::find_if(candidates.begin(), candidates.end(),
                          [&](const EffectCandidate& c) { return c.effect == name; });
  };
  // The accepted effects' values are the tail of the last step's theta (after the body's).
  FitPoint point = points.at(missing->effect);
  std::vector<const EffectCandidate*> accepted{candidate(missing->effect)};
  while (static_cast<int>(d.chain.size()) < options.max_effects && point.data > d.noise_gate * d.samples &&
         accepted.size() < candidates.size()) {
    if (accepted.back()->stand_in) {
      char note[400];
      std::snprintf(note, sizeof note,
                    "the chain stops at %s: its fit is a stand-in and stays at %.3g x the noise, a misfit that other "
                    "effects fitted on top of it would absorb; add its proper model, then run diagnose again",
                    accepted.back()->effect.c_str(), point.data / d.samples);
      d.chain_note = note;
      break;
    }
    std::map<std::string, FitPoint> step_points;
    std::vector<EffectFit> ranking = test_on_top(fit, candidates, accepted, point, b, options, d, step_points);
    const EffectFit* next = first_significant(ranking);
    if (!next) {
      d.after_chain = std::move(ranking);
      break;
    }
    ChainStep st = chain_step(*next, d);
    point = step_points.at(next->effect);
    accepted.push_back(candidate(next->effect));
    st.ranking = std::move(ranking);
    d.chain.push_back(std::move(st));
  }
}

// The first significant effect, the model's parameters that moved beyond
// what the rig file states, and the one-line verdict.
void conclude(Diagnosis& d, const DiagnosisOptions& options) {
  const EffectFit* missing = first_significant(d.ranking);
  if (missing) {
    d.missing_effect = missing->effect;
    d.body = d.chain.empty() ? missing->body : d.chain.back().body;
  }
  for (const auto& p : d.body) {
    if (p.off) d.parameters_off.push_back(p);
  }
  std::vector<const EffectFit*> alike;
  for (const auto& e : d.ranking) {
    if (missing && &e != missing && e.significant && e.versus_first_p > options.discrimination) {
      alike.push_back(&e);
      d.indistinguishable.push_back(e.effect);
    }
  }
  if (d.missing_effect) {
    d.summary = "missing effect: " + *d.missing_effect;
    if (!alike.empty()) {
      d.summary += ", or";
      for (size_t i = 0; i < alike.size(); ++i) d.summary += (i ? ", " : " ") + alike[i]->effect;
      char p[64];
      std::snprintf(p, sizeof p, "%.2g", alike.front()->versus_first_p);
      d.summary += std::string(": the records cannot tell them apart (Vuong's test, p = ") + p +
                   "); measurements that show each directly: " + missing->effect + ": " + missing->evidence;
      for (const auto* e : alike) d.summary += "; " + e->effect + ": " + e->evidence;
    }
    if (d.chain.size() > 1) {
      d.summary += "; with it in the model, then";
      for (size_t i = 1; i < d.chain.size(); ++i) d.summary += (i > 1 ? ", then " : " ") + d.chain[i].effect;
      char r[160];
      std::snprintf(r, sizeof r, " (residual %.3g x the noise without them, %.3g x with all)", d.noise_ratio,
                    d.chain.back().noise_ratio);
      d.summary += r;
    }
  } else if (d.noise_ratio <= d.noise_gate) {
    d.summary =
        "no significant missing effect: the model matches the measurements to the noise (and the "
        "simulator's numerics)";
  } else {
    d.summary = "no significant missing effect: no effect of the catalogue explains the residual";
  }
  if (!d.parameters_off.empty()) {
    d.summary += "; model parameter off:";
    for (size_t i = 0; i < d.parameters_off.size(); ++i) {
      d.summary += (i ? ", " : " ") + describe_off(d.parameters_off[i]);
    }
  }
}

// The frames in the model, as "; ..." for a verdict on a model above the
// noise: a frame stiffer or softer than its model shows as other effects.
// Held as given (no uncertainty of their stiffness: `{stiffness: 0}` in a
// rig file, or a model built without one), the user is told how to have
// the stiffness refitted, whatever was found (measured on examples/large-rig, its FE
// fixed frame 40 % too stiff: 1.7e7 x the noise, named rod_compliance and
// then a carrying frame; with the frame's stiffness refitted, -40 % at
// 0.84 x the noise). Refitted, the factor scales the whole frame: a frame
// model off in its shape - a member group stiffer or softer than the rest
// - is left to other effects, which is said where what was found leaves
// the model above the noise (the large rig's columns' wall 20 % thinner in
// the records: a carrying frame's stand-in named, its chain ending at 81 x
// the noise; docs/compare.md).
std::string frames_note(const rig::RigModel& model, const Diagnosis& d) {
  if (!(d.noise_ratio > d.noise_gate)) return "";
  const double end = d.chain.empty() ? d.noise_ratio : d.chain.back().noise_ratio;
  std::string held, refitted;
  for (const auto& e : model.effects) {
    const bool frame = dynamic_cast<const rig::FixedFrameFlexibility*>(e.get()) ||
                       dynamic_cast<const rig::CarryingFrameFlexibility*>(e.get());
    if (!frame) continue;
    const bool stated = std::any_of(model.effect_uncertainty.begin(), model.effect_uncertainty.end(),
                                    [&](const rig::EffectUncertainty& u) { return u.effect == e->name(); });
    std::string& list = stated ? refitted : held;
    list += std::string(list.empty() ? "" : " and ") + e->name();
  }
  std::string note;
  if (!held.empty()) {
    note += "; the model's " + held +
            " held as given: a frame stiffer or softer than its model shows as other effects - state "
            "effects.<frame>.uncertainty.stiffness above 0 (its relative standard deviation; without it 0.1) to have "
            "its stiffness refitted";
  }
  if (!refitted.empty() && end > d.noise_gate) {
    note += "; the model's " + refitted +
            " refitted as one factor on its stiffness, and the model still above the noise: a frame model off in "
            "its shape (a member group stiffer or softer than the rest) shows as other effects - check the "
            "frame's model";
  }
  return note;
}

}  // namespace

ShownUnit shown_unit(const std::string& unit) {
  if (unit == "m") return {1e3, " mm"};
  return {1.0, unit == "1" ? "" : " " + unit};
}

std::string describe_off(const FittedParameter& p) {
  const ShownUnit u = shown_unit(p.unit);
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s %+.4g%s (stated +-%.3g)", p.name.c_str(), u.scale * p.value, u.suffix.c_str(),
                u.scale * p.prior_std);
  return buf;
}

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
  Fitter fit(model, base, targets, body_parameters(model), options.threads);
  Fitter held(model, base, targets, BodyParameters{}, options.threads);
  const Baseline b = fit_baseline(fit, model, base, targets, states, options, d);
  d.numerics_ratio = period_error_residual(targets, options.period_tolerance) / d.samples;
  d.noise_gate = gate_ratio(options, d.numerics_ratio);
  // Within the gate every significance test applies (score): no effect can be significant.
  const bool at_noise = b.at.data <= d.noise_gate * d.samples;
  if (at_noise) d.body = body_values(fit, b.at, b.schur_inverse, d);
  for (const auto& e : model.effects) d.present.push_back(e->name());
  const std::vector<EffectCandidate> candidates = candidates_to_test(base, d.present, options);
  if (at_noise && !options.rank_at_noise && !candidates.empty()) {
    char note[200];
    std::snprintf(note, sizeof note,
                  "no candidate was fitted: the model as it is reaches the noise (%.3g x, the threshold %.3g x), "
                  "where no effect can be significant; rank_at_noise (--rank-all) fits them",
                  d.noise_ratio, d.noise_gate);
    d.ranking_note = note;
    conclude(d, options);
    return d;
  }
  std::map<std::string, FitPoint> points;  // of the ranking's fits: the look-alike test, the chain
  const Reference ref{b.at.data, b.dof, 0};
  std::vector<CandidateFits> fits;
  for (size_t k = 0; k < candidates.size(); ++k) {
    const EffectCandidate& c = candidates[k];
    progress(options,
             "fitting " + c.effect + " (" + std::to_string(k + 1) + " of " + std::to_string(candidates.size()) + ")");
    fits.push_back(fit_candidate(fit, held, c, b, options));
    d.ranking.push_back(score(fit, c, fits.back(), ref, d, options));
  }
  converge_contenders(fit, candidates, fits, b, ref, records, options, d);
  for (size_t k = 0; k < candidates.size(); ++k) points[candidates[k].effect] = std::move(fits[k].joint.at);
  rank(d.ranking, d, b.dof);
  discriminate_against_first(d, points, targets);
  follow_chain(fit, candidates, b, points, options, d);
  conclude(d, options);
  d.summary += frames_note(model, d);
  return d;
}

}  // namespace rigflex::diagnose
