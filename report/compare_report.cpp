// The compare and diagnose reports.
#include "report/reports.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>

#include "diagnose/model_response.hpp"
#include "report/report_text.hpp"

namespace rigflex::report {
namespace {

using namespace text;

// ---------------------------------------------------------------- shared sections

// Per history: source, errors, the swing-state fit.
void history_table(HtmlReport& r, const std::vector<diagnose::HistoryComparison>& hs, Eigen::Index channels) {
  if (hs.empty()) return;
  const Eigen::Index n = channels / 3;
  Table t{{"history", "source", "samples", "overall NRMSE", "force NRMSE", "angle NRMSE", "NRMSE over the fit window",
           "overall NRMSE, raw", "fit converged (iterations)", "band residual / noise"},
          {}};
  // RMS over a channel range of per-channel values; none when not computed.
  auto rms = [&](const Eigen::VectorXd& v, Eigen::Index first, Eigen::Index count) {
    return v.size() == channels && channels > 0 ? diagnose::rms_of(v, first, count) : kNaN;
  };
  for (size_t k = 0; k < hs.size(); ++k) {
    const auto& h = hs[k];
    t.rows.push_back({std::to_string(k + 1), h.source, str(h.t().size()), num(rms(h.nrmse, 0, channels)),
                      num(rms(h.nrmse, 0, n)), num(rms(h.nrmse, n, 2 * n)), num(h.fit_window_nrmse),
                      num(rms(h.raw_nrmse, 0, channels)),
                      yes_no(h.fit.converged) + " (" + std::to_string(h.fit.iterations) + ")", num(h.fit.whitened_rms)});
  }
  r.table(t, "Histories (NRMSE in the swing band; raw: every sample, noise and ringing included)");
}

enum class Curves { measured_and_model, residual };

// One channel of one history, a small multiple: measured and model, or the residual.
Plot channel_plot(const diagnose::HistoryComparison& h, const std::vector<double>& t, const Eigen::MatrixXd& residual,
                  const std::string& name, Eigen::Index c, Curves curves) {
  Plot p;
  p.title = name;
  p.x_label = "t (s)";
  const std::string unit = channel_unit(name);
  if (curves == Curves::residual) {
    p.series.push_back({"measured − model", t, column(residual, c), false, {}});
    p.y_label = "residual (" + unit + ")";
  } else {
    p.series.push_back({"measured", t, column(h.measured(), c), false, {}});
    p.series.push_back({"model", t, column(h.model, c), false, kDash});
    p.y_label = name + " (" + unit + ")";
  }
  // A third of a page's width shows no more than this many points.
  p.max_points = kSmallPlotPoints;
  return p;
}

// Every channel of one history, a small plot each: the rods across, forces,
// alpha and beta down (one chart of twelve curves reads as none).
void history_plots(HtmlReport& r, const diagnose::HistoryComparison& h, const std::vector<std::string>& names,
                   Curves curves) {
  const auto n = static_cast<Eigen::Index>(names.size() / 3);
  if (n == 0) return;
  const std::vector<double> t = values(h.t());
  const Eigen::MatrixXd residual = curves == Curves::residual ? h.residual() : Eigen::MatrixXd();
  std::vector<Plot> plots;
  for (Eigen::Index c = 0; c < 3 * n; ++c)
    plots.push_back(channel_plot(h, t, residual, names[static_cast<size_t>(c)], c, curves));
  r.small_multiples(plots, static_cast<int>(n),
                    (curves == Curves::residual ? "Residual (measured − model) per channel, "
                                                : "Measured (solid) and model (dashed) per channel, ") +
                        short_source(h.source) + ": load cells, then encoder angles alpha and beta, a rod per column");
}

// A line per mode of the model; modes of one kind within 15 % of each other
// (the three swing modes, the rods' bounce modes) share one label, which
// would otherwise overprint.
std::vector<PlotMarker> mode_markers(const diagnose::ResidualAnalysis& a) {
  std::vector<std::pair<double, std::string>> modes;
  for (size_t k = 0; k < a.mode_frequencies_hz.size(); ++k)
    if (a.mode_frequencies_hz[k] > 0 && std::isfinite(a.mode_frequencies_hz[k]))
      modes.emplace_back(a.mode_frequencies_hz[k], k < a.mode_kinds.size() ? a.mode_kinds[k] : "mode");
  std::sort(modes.begin(), modes.end());
  std::vector<PlotMarker> m;
  for (size_t k = 0; k < modes.size();) {
    size_t end = k + 1;
    while (end < modes.size() && modes[end].second == modes[k].second && modes[end].first <= 1.15 * modes[k].first)
      ++end;
    std::string label = modes[k].second + " ";
    for (size_t j = k; j < end; ++j) label += (j > k ? ", " : "") + fmt("%.3g", modes[j].first);
    m.push_back({modes[k].first, label + " Hz"});
    for (size_t j = k + 1; j < end; ++j) m.push_back({modes[j].first, ""});
    k = end;
  }
  return m;
}

void spectrum_plot(HtmlReport& r, const diagnose::ResidualAnalysis& a, const Eigen::VectorXd& residual,
                   const Eigen::VectorXd& measured, const std::string& group, const std::string& unit) {
  const diagnose::ResidualSpectra& s = a.spectra;
  Plot p;
  p.title = "Residual spectrum, " + group;
  p.x_label = "f (Hz)";
  p.y_label = "amplitude spectral density (" + unit + "/√Hz)";
  p.log_x = p.log_y = true;
  p.series.push_back({"residual", values(s.frequency_hz), values(residual), false, {}});
  p.series.push_back({"measured", values(s.frequency_hz), values(measured), false, kDash});
  p.markers = mode_markers(a);
  r.plot(p);
}

void peaks_table(HtmlReport& r, const diagnose::ResidualSpectra& s) {
  if (s.peaks.empty()) return;
  Table t{{"group", "frequency (Hz)", "amplitude spectral density", "nearest model mode (Hz)"}, {}};
  for (const auto& p : s.peaks)
    t.rows.push_back({p.group, num(p.frequency_hz), num(p.amplitude), p.nearest_mode_hz > 0 ? num(p.nearest_mode_hz) : "none"});
  r.table(t, "Largest residual peaks");
}

void spectra_section(HtmlReport& r, const diagnose::ResidualAnalysis& a) {
  const diagnose::ResidualSpectra& s = a.spectra;
  if (s.frequency_hz.size() == 0) return;
  r.heading("Residual spectra");
  r.paragraph(
      "Welch estimates averaged over the group's channels and the histories: the residual (solid) beside the measured "
      "signal (dashed). Dashed vertical lines: the model's modes. A residual peak beside a mode points to a wrong "
      "stiffness or mass; a peak without a mode to a mode the model lacks.");
  spectrum_plot(r, a, s.residual_force, s.measured_force, "forces", "N");
  spectrum_plot(r, a, s.residual_angle, s.measured_angle, "angles", "rad");
  peaks_table(r, s);
}

void trend_section(HtmlReport& r, const diagnose::ResidualAnalysis& a) {
  if (a.trend_t.empty()) return;
  r.heading("Error along the record");
  r.paragraph("Overall NRMSE per window, pooled over the histories; least-squares slope " +
              fmt("%+.4g", a.trend_slope) + " per s (growing: the model drifts away from the measurement).");
  Plot p;
  p.title = "Overall NRMSE per window";
  p.x_label = "t from the record's start (s)";
  p.y_label = "overall NRMSE (residual RMS / signal std)";
  p.series.push_back({"overall NRMSE", a.trend_t, a.trend_nrmse, false, {}});
  r.plot(p);
}

void decay_section(HtmlReport& r, const diagnose::ResidualAnalysis& a, const std::vector<std::string>& sources) {
  if (a.decay.empty()) return;
  r.heading("Swing decay");
  r.paragraph("Exponential decay rate of the swing amplitude (angle channels) per history, measured and model; mean "
              "extra decay (measured − model) " +
              fmt("%+.4g", a.extra_decay_rate) + " 1/s. Extra decay growing with amplitude points to drag, constant "
              "per swing to friction.");
  Plot p;
  p.kind = Plot::Kind::bar;
  p.title = "Decay rate per history";
  p.x_label = "history";
  p.y_label = "decay rate (1/s)";
  PlotSeries measured{"measured", {}, {}, false, {}}, model{"model", {}, {}, false, {}};
  for (const auto& d : a.decay) {
    p.categories.push_back(history_label(sources, d.history));
    measured.y.push_back(d.measured_rate);
    model.y.push_back(d.model_rate);
  }
  p.series = {measured, model};
  r.plot(p);
}

void analysis_sections(HtmlReport& r, const diagnose::ResidualAnalysis& a, const std::vector<std::string>& sources) {
  spectra_section(r, a);
  trend_section(r, a);
  decay_section(r, a, sources);
}

// ---------------------------------------------------------------- compare

void check_comparison(const diagnose::ModelComparison& c) {
  const auto C = static_cast<Eigen::Index>(c.channels.size());
  check_histories(c.histories, C, "compare report");
  check_per_channel(c.nrmse, C, "compare report: nrmse");
  check_per_channel(c.raw_nrmse, C, "compare report: raw_nrmse");
  check_analysis(c.analysis, C, "compare report");
}

void compare_summary(HtmlReport& r, const diagnose::ModelComparison& c, const CompareContext& ctx) {
  r.heading("Summary");
  Table t{{"quantity", "value"},
          {{"rig", ctx.rig},
           {"model", ctx.model_label},
           {"added effects", joined(ctx.model_effects, "none")},
           {"histories", std::to_string(c.histories.size())},
           {"overall NRMSE", num(c.overall_nrmse)},
           {"force NRMSE", num(c.force_nrmse)},
           {"angle NRMSE", num(c.angle_nrmse)},
           {"overall NRMSE, raw", num(c.raw_overall_nrmse)},
           {"force NRMSE, raw", num(c.raw_force_nrmse)},
           {"NRMSE trend (per s)", fmt("%+.4g", c.analysis.trend_slope)},
           {"extra decay, measured − model (1/s)", fmt("%+.4g", c.analysis.extra_decay_rate)}}};
  r.table(t, "Model against measurements (NRMSE: RMS of the residual / standard deviation of the signal, in the "
             "swing band; raw: every sample, noise and the frames' ringing included)");
  for (const auto& w : c.warnings) r.paragraph("Warning: " + w);
}

void channel_table(HtmlReport& r, const diagnose::ModelComparison& c) {
  if (c.channels.empty()) return;
  const diagnose::ResidualAnalysis& a = c.analysis;
  Table t{{"channel", "NRMSE", "NRMSE, raw", "residual / noise", "noise σ", "static offset", "offset / its std error",
           "share of the residual", "lag-1 autocorrelation"},
          {}};
  for (size_t k = 0; k < c.channels.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const std::string unit = " " + channel_unit(c.channels[k]);
    t.rows.push_back({c.channels[k], num(at(c.nrmse, i)), num(at(c.raw_nrmse, i)), fmt("%.2f", at(a.noise_ratio, i)), num(at(a.noise, i)) + unit,
                      num(at(a.static_offset, i)) + unit, fmt("%+.1f", at(a.offset_in_noise, i)),
                      percent(at(a.channel_share, i)), fmt("%+.2f", at(a.lag1, i))});
  }
  r.table(t, "Per channel, pooled over the histories (residual / noise 1: the model is at the noise)");
}

void correlation_table(HtmlReport& r, const std::vector<diagnose::StateCorrelation>& cs,
                       const std::vector<std::string>& channels) {
  if (cs.empty()) return;
  bool per = !channels.empty();
  for (const auto& s : cs) per = per && s.per_channel.size() == static_cast<Eigen::Index>(channels.size());
  Table t{{"state", "largest |correlation|", "channel"}, {}};
  if (per) t.header.insert(t.header.end(), channels.begin(), channels.end());
  for (const auto& s : cs) {
    std::vector<std::string> row{s.state, fmt("%+.2f", s.largest), s.channel};
    for (Eigen::Index i = 0; per && i < s.per_channel.size(); ++i) row.push_back(fmt("%+.2f", s.per_channel(i)));
    t.rows.push_back(row);
  }
  r.heading("Residual against the states");
  r.table(t, "Correlation of each channel's residual with its rod's state (sign of velocity: friction; velocity: "
             "damping; angle: stiffness or geometry)");
}

void windows_table(HtmlReport& r, const std::vector<diagnose::ResidualWindow>& ws, const std::vector<std::string>& sources) {
  if (ws.empty()) return;
  Table t{{"rank", "history", "from (s)", "to (s)", "share of the residual"}, {}};
  for (size_t k = 0; k < ws.size(); ++k)
    t.rows.push_back({std::to_string(k + 1), history_label(sources, ws[k].history), fmt("%.2f", ws[k].t_start),
                      fmt("%.2f", ws[k].t_end), percent(ws[k].share)});
  r.table(t, "Time windows with the largest noise-weighted residual");
}

void study_section(HtmlReport& r, const std::vector<StudyEntry>& study) {
  if (study.empty()) return;
  r.heading("Error by model version");
  Plot p;
  p.kind = Plot::Kind::bar;
  p.title = "NRMSE per model version";
  p.x_label = "model version";
  p.y_label = "NRMSE (residual RMS / signal std)";
  PlotSeries overall{"overall NRMSE", {}, {}, false, {}}, force{"force NRMSE", {}, {}, false, {}};
  Table t{{"version", "model", "effects", "overall NRMSE", "force NRMSE", "angle NRMSE", "identified zG (mm)"}, {}};
  for (const auto& e : study) {
    p.categories.push_back("v" + std::to_string(e.version) + " " + e.label);
    overall.y.push_back(e.overall_nrmse);
    force.y.push_back(e.force_nrmse);
    t.rows.push_back({std::to_string(e.version), e.label, joined(e.effects, "none"), num(e.overall_nrmse),
                      num(e.force_nrmse), num(e.angle_nrmse),
                      e.identified_cog_z ? fmt("%.2f", 1e3 * *e.identified_cog_z) : "–"});
  }
  p.series = {overall, force};
  r.plot(p);
  r.table(t, "Model versions of the study");
}


void identified_table(HtmlReport& r, const identify::IdentificationResult& id, const std::optional<fe::MassProperties>& ref) {
  Table t{{"quantity", "identified", "std (least squares)"}, {}};
  if (ref) t.header.insert(t.header.end(), {"reference", "identified − reference"});
  std::vector<const fe::MassProperties*> shown{&id.properties};
  if (ref) shown.push_back(&*ref);
  const auto q = mass_quantities(shown);
  const auto a = quantities_of(id.properties);
  const auto b = ref ? quantities_of(*ref) : std::array<double, 10>{};
  for (size_t i = 0; i < 10; ++i) {
    std::vector<std::string> cells{q[i].name, q[i](a[i]), i == 0 ? "–" : q[i](id.standard_deviation[i - 1])};
    if (ref) cells.insert(cells.end(), {q[i](b[i]), q[i](a[i] - b[i])});
    t.rows.push_back(cells);
  }
  r.table(t, "Identified mass properties (inertia about the CoG, products as negative integrals; inertia std of the "
             "solve's unknowns, about P)");
}

void identified_section(HtmlReport& r, const diagnose::ModelComparison& c, const CompareContext& ctx) {
  r.heading("Identified mass properties");
  const std::string alg = identify::to_string(c.algorithm);
  if (!c.identified) {
    r.paragraph(c.identification_error.empty() ? "Not identified."
                                               : "Not identified (" + alg + " algorithm): " + c.identification_error);
    return;
  }
  const identify::IdentificationResult& id = *c.identified;
  r.paragraph("From the same records with the model's algorithm (" + alg + "), " + std::to_string(id.equations) +
              " equation times; condition number " + num(id.condition_number) + ", inertia positive definite: " +
              yes_no(id.positive_definite) + ", triangle inequality: " + yes_no(id.triangle_inequality) +
              (ctx.reference ? "." : "; no reference given."));
  identified_table(r, id, ctx.reference);
}

// ---------------------------------------------------------------- diagnosis

Eigen::Index check_baseline(const diagnose::Diagnosis& d) {
  const Eigen::Index C = d.baseline.empty() ? 0 : d.baseline.front().measured().cols();
  check_histories(d.baseline, C, "diagnosis report: baseline");
  return C;
}

void verdict_section(HtmlReport& r, const diagnose::Diagnosis& d, const CompareContext& ctx) {
  r.heading("Verdict");
  std::string verdict = d.summary;
  if (verdict.empty())
    verdict = d.missing_effect ? "missing effect: " + *d.missing_effect : "no significant missing effect";
  r.paragraph(verdict);
  r.paragraph("Model: " + ctx.model_label + (ctx.rig.empty() ? "" : " (rig " + ctx.rig + ")") +
              ".\nEffects the model has (not tested): " + joined(d.present, "none") +
              ".\nBaseline residual: " + fmt("%.3g", d.noise_ratio) + " × the noise (1: at the noise), over " +
              fmt("%.0f", d.samples) + " band samples × channels, independent share " + fmt("%.3g", d.independence) +
              ".\nGate: " + fmt("%.3g", d.noise_gate) + " × the noise (the noise, and a simulator's period error: " +
              fmt("%.3g", d.numerics_ratio) + " × here); below it no effect is significant.");
}

// A YAML block for a paragraph, whose style (pre-line) would collapse the
// indentation: leading spaces become no-break spaces (shown, not collapsed).
std::string keep_indentation(const std::string& block) {
  std::string out;
  bool leading = true;
  for (const char c : block) {
    if (leading && c == ' ') {
      out += "\u00a0";
      continue;
    }
    leading = c == '\n';
    out += c;
  }
  return out;
}

std::string ranked_name(const diagnose::EffectFit& e) { return e.effect + (e.significant ? " *" : ""); }

void ranking_section(HtmlReport& r, const diagnose::Diagnosis& d) {
  if (d.ranking.empty()) {
    r.paragraph(d.ranking_note.empty()
                    ? "No effect was tested (the model has every effect of the catalogue, or none was selected)."
                    : "No effect was tested: " + d.ranking_note + ".");
    return;
  }
  r.heading("Effects ranked by the share of the residual they explain");
  Plot p;
  p.kind = Plot::Kind::bar;
  p.title = "Share of the baseline residual explained (* significant)";
  p.x_label = "candidate effect";
  p.y_label = "explained (%)";
  PlotSeries s{"explained (re-simulated)", {}, {}, false, {}};
  Table t{{"rank", "effect", "explained", "linearization predicted", "significant", "plausible", "p-value",
           "F statistic", "refinements", "note"},
          {}};
  for (size_t k = 0; k < d.ranking.size(); ++k) {
    const diagnose::EffectFit& e = d.ranking[k];
    p.categories.push_back(ranked_name(e));
    s.y.push_back(100 * e.explained_fraction);
    t.rows.push_back({std::to_string(k + 1), e.effect, percent(e.explained_fraction),
                      percent(e.linear_explained_fraction), yes_no(e.significant), yes_no(e.plausible),
                      fmt("%.3g", e.p_value), fmt("%.4g", e.f_statistic), std::to_string(e.refinements), e.note});
  }
  p.series = {s};
  r.plot(p);
  r.table(t, "Ranking");
}

void parameters_table(HtmlReport& r, const diagnose::Diagnosis& d) {
  Table t{{"effect", "parameter", "value ± std", "unit", "plausible range", "plausible"}, {}};
  for (const auto& e : d.ranking)
    for (const auto& p : e.parameters)
      t.rows.push_back({e.effect, p.name, plus_minus(p.value, p.std, "%.4g"), p.unit,
                        fmt("%.4g", p.low) + " … " + fmt("%.4g", p.high), yes_no(p.plausible)});
  if (!t.rows.empty()) r.table(t, "Fitted parameters");
}

void missing_effect_section(HtmlReport& r, const diagnose::Diagnosis& d) {
  if (!d.missing_effect) return;
  const auto e = std::find_if(d.ranking.begin(), d.ranking.end(),
                              [&](const diagnose::EffectFit& x) { return x.effect == *d.missing_effect; });
  r.heading("Missing effect: " + *d.missing_effect);
  if (e == d.ranking.end()) return;
  if (!e->plausible) r.paragraph("Warning: some fitted values lie outside their plausible range.");
  if (!e->advice.empty()) r.paragraph("To capture it properly: " + e->advice + ".");
  if (!d.indistinguishable.empty()) {
    std::string alike = "The records cannot tell it from " + joined(d.indistinguishable, "") +
                        ". A measurement that shows it directly: " + e->evidence + ".";
    for (const auto& x : d.ranking) {
      if (std::find(d.indistinguishable.begin(), d.indistinguishable.end(), x.effect) == d.indistinguishable.end())
        continue;
      alike += "\n" + x.effect + ": " + x.evidence + " (Vuong's test against " + e->effect + ": p = " +
               fmt("%.2g", x.versus_first_p) + ").";
    }
    r.paragraph(alike);
  }
  if (!e->rig_block.empty())
    r.paragraph("The fitted effect, for the rig file under `effects:` (rigflex diagnose writes it as effects/" +
                e->effect + ".yaml in its output folder, ready for `rigflex compare --effects`):\n" +
                keep_indentation(e->rig_block));
}

std::string ranked_names(const std::vector<diagnose::EffectFit>& fits) {
  std::vector<std::string> names;
  for (const auto& e : fits) names.push_back(ranked_name(e));
  return joined(names, "");
}

// The effects accepted one after another, the residual after each: the
// error falling step by step, and the block that adds them all.
void chain_section(HtmlReport& r, const diagnose::Diagnosis& d) {
  if (d.chain.size() < 2 && d.after_chain.empty() && d.chain_note.empty()) return;
  r.heading("The chain: effects added one after another");
  Table t{{"step", "effect added", "residual / noise", "p-value", "tested at this step"}, {}};
  t.rows.push_back({"0", "(the model as it is)", fmt("%.3g", d.noise_ratio), "", ""});
  for (size_t k = 0; k < d.chain.size(); ++k) {
    const diagnose::ChainStep& st = d.chain[k];
    t.rows.push_back({std::to_string(k + 1), st.effect, fmt("%.3g", st.noise_ratio), fmt("%.3g", st.p_value),
                      k == 0 ? "the ranking above" : ranked_names(st.ranking)});
  }
  r.table(t, "Chain (each step refits every effect before it, the body and the swing states)");
  if (!d.after_chain.empty())
    r.paragraph("Tested on top of the whole chain, none significant: " + ranked_names(d.after_chain) + ".");
  if (!d.chain_note.empty()) r.paragraph("Note: " + d.chain_note + ".");
  if (!d.chain.empty() && !d.chain.back().rig_block.empty())
    r.paragraph("Every effect of the chain as its last step fitted them, for the rig file under `effects:` "
                "(rigflex diagnose writes it as effects/found.yaml):\n" +
                keep_indentation(d.chain.back().rig_block));
}

// compare's refit of the body (and the parameters whose uncertainty the rig
// file states): the offsets to correct in the rig file, those beyond what
// it states marked.
void model_fit_section(HtmlReport& r, const diagnose::ModelComparison& c) {
  if (!c.model_fit) return;
  const diagnose::ModelParameterFit& f = *c.model_fit;
  r.heading("The model's own parameters refitted");
  if (!f.credible) {
    r.paragraph("Not used: refitted, the model stays at " + fmt("%.3g", f.noise_ratio) + " x the noise (" +
                fmt("%.3g", f.noise_ratio_as_stated) +
                " x as the rig file states it); there the offsets would absorb a missing effect. The figures above "
                "are the rig file's model's; run rigflex diagnose.");
    return;
  }
  r.paragraph("Residual / noise " + fmt("%.3g", f.noise_ratio_as_stated) + " as the rig file states the model, " +
              fmt("%.3g", f.noise_ratio) + " refitted; force NRMSE " +
              fmt("%.4f", c.as_stated ? c.as_stated->force : 0.0) + " -> " + fmt("%.4f", c.force_nrmse) +
              ". The figures above are the refitted model's.");
  Table t{{"parameter", "offset from the rig file", "std", "stated std", "off"}, {}};
  for (const auto& p : f.parameters) {
    const diagnose::ShownUnit u = diagnose::shown_unit(p.unit);
    t.rows.push_back({p.name, fmt("%+.4g", u.scale * p.value) + u.suffix, fmt("%.3g", u.scale * p.std),
                      fmt("%.3g", u.scale * p.prior_std), p.off ? "OFF" : ""});
  }
  r.table(t, "Offsets beyond 3 stated standard deviations are marked OFF: correct them in the rig file");
}

void baseline_section(HtmlReport& r, const diagnose::Diagnosis& d, Eigen::Index channels,
                      const diagnose::ResidualAnalysis* analysis) {
  if (d.baseline.empty()) return;
  r.heading("Baseline: the model as it is");
  history_table(r, d.baseline, channels);
  history_plots(r, d.baseline.front(), diagnose::channel_names(static_cast<int>(channels / 3)), Curves::residual);
  if (analysis) analysis_sections(r, *analysis, sources_of(d.baseline));
}

}  // namespace

HtmlReport compare_report(const diagnose::ModelComparison& c, const CompareContext& ctx,
                          const std::vector<StudyEntry>& study) {
  check_comparison(c);
  HtmlReport r("rigflex compare: " + (ctx.rig.empty() ? std::string("model against measurements") : ctx.rig));
  compare_summary(r, c, ctx);
  channel_table(r, c);
  history_table(r, c.histories, static_cast<Eigen::Index>(c.channels.size()));
  if (!c.histories.empty() && !c.channels.empty()) {
    r.heading("First history: " + short_source(c.histories.front().source));
    history_plots(r, c.histories.front(), c.channels, Curves::measured_and_model);
    history_plots(r, c.histories.front(), c.channels, Curves::residual);
  }
  const std::vector<std::string> sources = sources_of(c.histories);
  analysis_sections(r, c.analysis, sources);
  correlation_table(r, c.analysis.correlations, c.channels);
  windows_table(r, c.analysis.windows, sources);
  model_fit_section(r, c);
  study_section(r, study);
  identified_section(r, c, ctx);
  return r;
}

HtmlReport diagnosis_report(const diagnose::Diagnosis& d, const CompareContext& ctx,
                            const diagnose::ResidualAnalysis* baseline_analysis) {
  const Eigen::Index channels = check_baseline(d);
  if (baseline_analysis) {
    const auto C = baseline_analysis->channels.empty() ? channels
                                                       : static_cast<Eigen::Index>(baseline_analysis->channels.size());
    check_analysis(*baseline_analysis, C, "diagnosis report");
  }
  HtmlReport r("rigflex diagnose: " + (ctx.rig.empty() ? std::string("which effect does the model miss?") : ctx.rig));
  verdict_section(r, d, ctx);
  ranking_section(r, d);
  parameters_table(r, d);
  missing_effect_section(r, d);
  chain_section(r, d);
  baseline_section(r, d, channels, baseline_analysis);
  return r;
}

}  // namespace rigflex::report
