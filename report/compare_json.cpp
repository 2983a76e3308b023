#include "report/compare_json.hpp"

#include <cmath>

#include "report/json_write.hpp"
#include "io/mass_record.hpp"

namespace rigflex::report {
namespace {

using Json = nlohmann::ordered_json;

Json array(const Eigen::VectorXd& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(finite_or_null(v(i)));
  return a;
}

Json array(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(finite_or_null(x));
  return a;
}

Json per_channel(const std::vector<std::string>& names, const Eigen::VectorXd& v) {
  Json o = Json::object();
  for (size_t i = 0; i < names.size(); ++i) o[names[i]] = finite_or_null(v(static_cast<Eigen::Index>(i)));
  return o;
}

Json state_json(const diagnose::SwingState& s) {
  return Json{{"x_m", s(0)}, {"y_m", s(1)}, {"yaw_rad", s(2)},
              {"vx_m_s", s(3)}, {"vy_m_s", s(4)}, {"yaw_rate_rad_s", s(5)}};
}

Json identified_json(const diagnose::ModelComparison& c, const CompareContext& x) {
  Json j;
  j["algorithm"] = identify::to_string(c.algorithm);
  if (!c.identified) {
    j["error"] = c.identification_error;
    return j;
  }
  const identify::IdentificationResult& r = *c.identified;
  io::MassRecordStd sd;
  sd.mass = 0;
  for (int k = 0; k < 3; ++k) sd.cog[static_cast<size_t>(k)] = r.standard_deviation[static_cast<size_t>(k)];
  for (int k = 0; k < 6; ++k) sd.inertia[static_cast<size_t>(k)] = r.standard_deviation[static_cast<size_t>(3 + k)];
  j["properties"] = io::mass_record_json(r.properties, sd);
  if (x.reference) {
    j["reference"] = io::mass_record_json(*x.reference);
    const Eigen::Vector3d d = r.properties.cog - x.reference->cog;
    j["cog_difference_m"] = {d.x(), d.y(), d.z()};
  }
  return j;
}

// The body's fitted offsets from the rig file's values, by parameter.
Json body_offsets_json(const std::vector<diagnose::FittedParameter>& body) {
  Json o = Json::object();
  for (const auto& p : body) {
    o[p.name] = {{"offset", finite_or_null(p.value)},
                 {"std", finite_or_null(p.std)},
                 {"unit", p.unit},
                 {"stated_std", finite_or_null(p.prior_std)},
                 {"off", p.off}};
  }
  return o;
}
// compare's refit of the model's own parameters.
Json model_fit_json(const diagnose::ModelComparison& c) {
  const diagnose::ModelParameterFit& f = *c.model_fit;
  Json j;
  j["credible"] = f.credible;
  j["residual_to_noise_as_stated"] = finite_or_null(f.noise_ratio_as_stated);
  j["residual_to_noise"] = finite_or_null(f.noise_ratio);
  if (c.as_stated) {
    j["as_stated"] = {{"overall_nrmse", finite_or_null(c.as_stated->overall)},
                      {"force_nrmse", finite_or_null(c.as_stated->force)},
                      {"angle_nrmse", finite_or_null(c.as_stated->angle)}};
  }
  j["parameters"] = body_offsets_json(f.parameters);
  Json off = Json::array();
  for (const auto& p : f.off) off.push_back(p.name);
  j["model_parameters_off"] = off;
  return j;
}

// Per history: errors, the fitted swing and elastic states, noise.
Json histories_json(const std::vector<diagnose::HistoryComparison>& histories, const std::vector<std::string>& channels) {
  Json hs = Json::array();
  for (const auto& h : histories) {
    Json o;
    o["source"] = h.source;
    o["samples"] = h.t().size();
    o["sample_interval_s"] = h.target.record.step_s;
    o["nrmse"] = per_channel(channels, h.nrmse);
    const Eigen::Index n = h.nrmse.size() / 3;
    o["overall_nrmse"] = finite_or_null(diagnose::rms_of(h.nrmse, 0, h.nrmse.size()));
    o["force_nrmse"] = finite_or_null(diagnose::rms_of(h.nrmse, 0, n));
    o["raw_nrmse"] = per_channel(channels, h.raw_nrmse);
    o["fit_window_nrmse"] = finite_or_null(h.fit_window_nrmse);
    Json el = Json::array();
    for (Eigen::Index k = 0; k < h.elastic.amplitude.size(); ++k) {
      el.push_back({{"amplitude", finite_or_null(h.elastic.amplitude(k))}, {"rate", finite_or_null(h.elastic.rate(k))}});
    }
    o["elastic_state"] = el;
    o["swing_state"] = state_json(h.fit.state);
    o["fit"] = {{"iterations", h.fit.iterations}, {"converged", h.fit.converged},
                {"band_residual_to_noise", finite_or_null(h.fit.whitened_rms)}};
    o["noise"] = per_channel(channels, h.target.sigma);
    hs.push_back(o);
  }
  return hs;
}

// Where the model fails: the residual analysis.
Json where_it_fails_json(const diagnose::ResidualAnalysis& a, const std::vector<std::string>& channels) {
  Json w;
  w["noise"] = per_channel(channels, a.noise);
  w["residual_to_noise"] = per_channel(channels, a.noise_ratio);
  w["channel_share"] = per_channel(channels, a.channel_share);
  w["static_offset"] = per_channel(channels, a.static_offset);
  w["static_offset_in_noise"] = per_channel(channels, a.offset_in_noise);
  w["lag1_autocorrelation"] = per_channel(channels, a.lag1);
  w["trend"] = {{"t_s", array(a.trend_t)}, {"overall_nrmse", array(a.trend_nrmse)},
                {"slope_per_s", finite_or_null(a.trend_slope)}};
  Json windows = Json::array();
  for (const auto& win : a.windows) {
    windows.push_back({{"history", win.history + 1}, {"t_start_s", win.t_start}, {"t_end_s", win.t_end},
                       {"share", finite_or_null(win.share)}});
  }
  w["windows"] = windows;
  Json decay = Json::array();
  for (const auto& d : a.decay) {
    decay.push_back({{"history", d.history + 1}, {"measured_rate_per_s", finite_or_null(d.measured_rate)},
                     {"model_rate_per_s", finite_or_null(d.model_rate)}});
  }
  w["decay"] = decay;
  w["extra_decay_rate_per_s"] = finite_or_null(a.extra_decay_rate);
  Json corr = Json::object();
  for (const auto& s : a.correlations) {
    corr[s.state] = {{"largest", finite_or_null(s.largest)}, {"channel", s.channel}, {"per_channel", per_channel(channels, s.per_channel)}};
  }
  w["state_correlation"] = corr;
  Json modes = Json::array();
  for (size_t k = 0; k < a.mode_frequencies_hz.size(); ++k) {
    modes.push_back({{"frequency_hz", finite_or_null(a.mode_frequencies_hz[k])}, {"kind", a.mode_kinds[k]}});
  }
  w["model_modes"] = modes;
  Json peaks = Json::array();
  for (const auto& p : a.spectra.peaks) {
    peaks.push_back({{"group", p.group}, {"frequency_hz", finite_or_null(p.frequency_hz)}, {"amplitude", finite_or_null(p.amplitude)},
                     {"nearest_mode_hz", finite_or_null(p.nearest_mode_hz)}});
  }
  w["spectrum_peaks"] = peaks;
  {
    // Up to 50 Hz: the swing band and the first frame modes of real rigs.
    const diagnose::ResidualSpectra& sp = a.spectra;
    Eigen::Index bins = 0;
    while (bins < sp.frequency_hz.size() && sp.frequency_hz(bins) <= 50.0) ++bins;
    w["spectra"] = {{"frequency_hz", array(sp.frequency_hz.head(bins))},
                    {"residual_force", array(sp.residual_force.head(bins))},
                    {"residual_angle", array(sp.residual_angle.head(bins))},
                    {"measured_force", array(sp.measured_force.head(bins))},
                    {"measured_angle", array(sp.measured_angle.head(bins))}};
  }
  return w;
}

}  // namespace

Json compare_json(const diagnose::ModelComparison& c, const CompareContext& x) {
  Json j;
  j["rig"] = x.rig;
  j["model"] = x.model_label;
  j["model_effects"] = x.model_effects;
  j["channels"] = c.channels;
  j["overall_nrmse"] = finite_or_null(c.overall_nrmse);
  j["force_nrmse"] = finite_or_null(c.force_nrmse);
  j["angle_nrmse"] = finite_or_null(c.angle_nrmse);
  j["nrmse"] = per_channel(c.channels, c.nrmse);
  j["raw"] = {{"overall_nrmse", finite_or_null(c.raw_overall_nrmse)}, {"force_nrmse", finite_or_null(c.raw_force_nrmse)},
              {"nrmse", per_channel(c.channels, c.raw_nrmse)}};
  j["swing_band"] = {{"cutoff_hz", c.histories.front().target.band.cutoff_hz},
                     {"kernel_s", static_cast<double>(c.histories.front().target.band.kernel.size()) *
                                      c.histories.front().target.band.step_s}};
  j["warnings"] = c.warnings;
  j["histories"] = histories_json(c.histories, c.channels);
  j["where_it_fails"] = where_it_fails_json(c.analysis, c.channels);
  j["identified"] = identified_json(c, x);
  if (c.model_fit) j["model_fit"] = model_fit_json(c);
  return j;
}

namespace {
// The fitted values by name.
Json parameters_json(const std::vector<diagnose::FittedParameter>& parameters) {
  Json params = Json::object();
  for (const auto& p : parameters) {
    params[p.name] = {{"value", finite_or_null(p.value)}, {"std", finite_or_null(p.std)}, {"unit", p.unit},
                      {"plausible_range", {finite_or_null(p.low), finite_or_null(p.high)}}, {"plausible", p.plausible}};
  }
  return params;
}

// One candidate's fit: share explained, tests, fitted values.
Json effect_fit_json(const diagnose::EffectFit& e) {
  Json o;
  o["effect"] = e.effect;
  o["explained_fraction"] = finite_or_null(e.explained_fraction);
  o["significant"] = e.significant;
  o["plausible"] = e.plausible;
  o["parameters"] = parameters_json(e.parameters);
  o["body"] = body_offsets_json(e.body);
  o["linear_explained_fraction"] = finite_or_null(e.linear_explained_fraction);
  o["f_statistic"] = finite_or_null(e.f_statistic);
  o["p_value"] = finite_or_null(e.p_value);
  o["versus_first_p"] = finite_or_null(e.versus_first_p);
  o["refinements"] = e.refinements;
  o["advice"] = e.advice;
  o["evidence"] = e.evidence;
  o["rig_block"] = e.rig_block;
  if (!e.note.empty()) o["note"] = e.note;
  return o;
}

// The chain: each step's effect, the residual with it, every effect's
// refitted values, the block that adds them all, and the candidates tested
// at that step (on top of the steps before).
Json chain_json(const std::vector<diagnose::ChainStep>& chain) {
  Json out = Json::array();
  for (const auto& st : chain) {
    Json tested = Json::array();
    for (const auto& e : st.ranking) tested.push_back(effect_fit_json(e));
    out.push_back({{"effect", st.effect}, {"residual_to_noise", finite_or_null(st.noise_ratio)},
                   {"p_value", finite_or_null(st.p_value)}, {"parameters", parameters_json(st.parameters)},
                   {"body", body_offsets_json(st.body)}, {"body_credible", st.body_credible},
                   {"rig_block", st.rig_block}, {"tested", tested}});
  }
  return out;
}
}  // namespace

Json diagnosis_json(const diagnose::Diagnosis& d, const CompareContext& x) {
  Json j;
  j["rig"] = x.rig;
  j["model"] = x.model_label;
  j["model_effects"] = d.present;
  j["missing_effect"] = d.missing_effect ? Json(*d.missing_effect) : Json(nullptr);
  j["indistinguishable"] = d.indistinguishable;
  j["summary"] = d.summary;
  j["baseline"] = {{"residual_to_noise", finite_or_null(d.noise_ratio)},
                   {"band_samples", d.samples},
                   {"independent_share", finite_or_null(d.independence)},
                   {"gate", finite_or_null(d.noise_gate)},
                   {"numerics_allowance", finite_or_null(d.numerics_ratio)}};
  j["body"] = body_offsets_json(d.body);
  Json off = Json::array();
  for (const auto& p : d.parameters_off) off.push_back(p.name);
  j["model_parameters_off"] = off;
  Json ranking = Json::array();
  for (const auto& e : d.ranking) ranking.push_back(effect_fit_json(e));
  j["ranking"] = ranking;
  j["chain"] = chain_json(d.chain);
  Json after = Json::array();
  for (const auto& e : d.after_chain) after.push_back(effect_fit_json(e));
  j["tested_after_chain"] = after;
  j["chain_note"] = d.chain_note;
  j["ranking_note"] = d.ranking_note;
  return j;
}

}  // namespace rigflex::report
