#include "report/reports.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "identify/identification_rig.hpp"
#include "identify/mass_statistics.hpp"
#include "diagnose/model_response.hpp"

namespace rigflex::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::vector<double> kDash{6, 3};

// ---------------------------------------------------------------- text

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}
std::string num(double v) { return fmt("%.4g", v); }

// Fixed decimals; no "-0.00".
std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  std::string s = b;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}
std::string percent(double share) { return fmt("%.1f %%", 100 * share); }
std::string yes_no(bool b) { return b ? "yes" : "no"; }
std::string str(Eigen::Index i) { return std::to_string(i); }

std::string plus_minus(double value, double sd, const char* format) {
  return std::isfinite(sd) ? fmt(format, value) + " ± " + fmt(format, sd) : fmt(format, value);
}
std::string plus_minus(double value, double sd, int decimals) {
  return std::isfinite(sd) ? fixed(value, decimals) + " ± " + fixed(sd, decimals) : fixed(value, decimals);
}

std::string joined(const std::vector<std::string>& items, const std::string& none) {
  if (items.empty()) return none;
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// A history's name in short: the file name of its source.
std::string short_source(const std::string& source) {
  const std::string f = std::filesystem::path(source).filename().string();
  return f.empty() ? source : f;
}

std::string history_label(const std::vector<std::string>& sources, int k) {
  std::string s = "h" + std::to_string(k + 1);
  if (k >= 0 && static_cast<size_t>(k) < sources.size() && !sources[static_cast<size_t>(k)].empty())
    s += " " + short_source(sources[static_cast<size_t>(k)]);
  return s;
}

// ---------------------------------------------------------------- data

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }
std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index c) { return values(m.col(c)); }
double at(const Eigen::VectorXd& v, Eigen::Index i) { return i < v.size() ? v(i) : kNaN; }

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Per-channel vectors: one value per channel, or none (not computed).
void check_per_channel(const Eigen::VectorXd& v, Eigen::Index channels, const std::string& name) {
  require(v.size() == 0 || v.size() == channels,
          name + " has " + str(v.size()) + " values for " + str(channels) + " channels");
}

void check_history(const diagnose::HistoryComparison& h, Eigen::Index channels, const std::string& where) {
  const Eigen::MatrixXd& m = h.measured();
  require(m.cols() == channels, where + ": measured has " + str(m.cols()) + " channels, expected " + str(channels));
  require(m.rows() == h.t().size(), where + ": " + str(h.t().size()) + " times for " + str(m.rows()) + " samples");
  require(h.model.rows() == m.rows() && h.model.cols() == m.cols(),
          where + ": model is " + str(h.model.rows()) + " x " + str(h.model.cols()) + ", measured " + str(m.rows()) +
              " x " + str(m.cols()));
  check_per_channel(h.nrmse, channels, where + ": nrmse");
  check_per_channel(h.raw_nrmse, channels, where + ": raw_nrmse");
  check_per_channel(h.target.sigma, channels, where + ": noise (target.sigma)");
}

void check_histories(const std::vector<diagnose::HistoryComparison>& hs, Eigen::Index channels, const std::string& what) {
  require(channels % 3 == 0, what + ": " + str(channels) + " channels, not 3 per rod (F, alpha, beta)");
  for (size_t k = 0; k < hs.size(); ++k)
    check_history(hs[k], channels, what + ": history " + std::to_string(k + 1) + " (" + hs[k].source + ")");
}

void check_analysis(const diagnose::ResidualAnalysis& a, Eigen::Index channels, const std::string& what) {
  check_per_channel(a.noise, channels, what + ": analysis.noise");
  check_per_channel(a.noise_ratio, channels, what + ": analysis.noise_ratio");
  check_per_channel(a.static_offset, channels, what + ": analysis.static_offset");
  check_per_channel(a.offset_in_noise, channels, what + ": analysis.offset_in_noise");
  check_per_channel(a.channel_share, channels, what + ": analysis.channel_share");
  for (const auto& s : a.correlations) check_per_channel(s.per_channel, channels, what + ": correlation " + s.state);
  require(a.trend_t.size() == a.trend_nrmse.size(), what + ": analysis.trend_t has " + std::to_string(a.trend_t.size()) +
                                                        " values, trend_nrmse " + std::to_string(a.trend_nrmse.size()));
  const diagnose::ResidualSpectra& s = a.spectra;
  const Eigen::Index f = s.frequency_hz.size();
  for (const auto* v : {&s.residual_force, &s.residual_angle, &s.measured_force, &s.measured_angle})
    require(v->size() == f, what + ": a spectrum has " + str(v->size()) + " values for " + str(f) + " frequencies");
}

std::vector<std::string> sources_of(const std::vector<diagnose::HistoryComparison>& hs) {
  std::vector<std::string> s;
  for (const auto& h : hs) s.push_back(h.source);
  return s;
}

std::string channel_unit(const std::string& channel) { return channel.rfind('F', 0) == 0 ? "N" : "rad"; }

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

// One channel group of one history: channels [first, first + count).
void group_plot(HtmlReport& r, const diagnose::HistoryComparison& h, const std::vector<std::string>& names,
                Eigen::Index first, Eigen::Index count, const std::string& group, Curves curves) {
  Plot p;
  p.x_label = "t (s)";
  const std::string unit = channel_unit(names[static_cast<size_t>(first)]);
  const std::vector<double> t = values(h.t());
  const Eigen::MatrixXd residual = curves == Curves::residual ? h.residual() : Eigen::MatrixXd();
  for (Eigen::Index c = first; c < first + count; ++c) {
    const std::string& name = names[static_cast<size_t>(c)];
    if (curves == Curves::residual) {
      p.series.push_back({name, t, column(residual, c), false, {}});
    } else {
      p.series.push_back({name + " measured", t, column(h.measured(), c), false, {}});
      p.series.push_back({name + " model", t, column(h.model, c), false, kDash});
    }
  }
  p.title = group + (curves == Curves::residual ? ": residual (measured − model), " : ": measured and model, ") +
            short_source(h.source);
  p.y_label = (curves == Curves::residual ? "residual (" : group + " (") + unit + ")";
  r.plot(p);
}

// Forces and angles of one history.
void history_plots(HtmlReport& r, const diagnose::HistoryComparison& h, const std::vector<std::string>& names,
                   Curves curves) {
  const auto n = static_cast<Eigen::Index>(names.size() / 3);
  if (n == 0) return;
  group_plot(r, h, names, 0, n, "forces", curves);
  group_plot(r, h, names, n, 2 * n, "angles (alpha, beta)", curves);
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
  p.y_label = "overall NRMSE";
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
  p.y_label = "NRMSE";
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

// The ten quantities of a mass-properties record, as displayed: mass, CoG in
// mm, inertia with the decimals that give the largest moment five digits
// (0.1 kg m^2 for moments of thousands, as IdentificationReport::table()).
struct Quantity {
  std::string name;
  double scale;
  int decimals;
  std::string operator()(double v) const { return fixed(scale * v, decimals); }
  std::string operator()(double v, double sd) const { return plus_minus(scale * v, scale * sd, decimals); }
};

std::array<double, 10> quantities_of(const fe::MassProperties& p) {
  const auto c = identify::mass_components(p);
  std::array<double, 10> q{p.mass};
  std::copy(c.begin(), c.end(), q.begin() + 1);
  return q;
}

std::array<Quantity, 10> mass_quantities(const std::vector<const fe::MassProperties*>& shown) {
  double largest = 0;
  for (const auto* p : shown)
    for (int i = 0; i < 3; ++i)
      if (std::isfinite(p->inertia(i, i))) largest = std::max(largest, std::abs(p->inertia(i, i)));
  const int d = largest > 0 ? std::clamp(4 - static_cast<int>(std::floor(std::log10(largest))), 0, 9) : 4;
  return {{{"m (kg)", 1, 2},
           {"xG (mm)", 1e3, 2},
           {"yG (mm)", 1e3, 2},
           {"zG (mm)", 1e3, 2},
           {"Jxx (kg m²)", 1, d},
           {"Jyy (kg m²)", 1, d},
           {"Jzz (kg m²)", 1, d},
           {"Jxy (kg m²)", 1, d},
           {"Jxz (kg m²)", 1, d},
           {"Jyz (kg m²)", 1, d}}};
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
              ".");
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
    r.paragraph("No effect was tested (the model has every effect of the catalogue, or none was selected).");
    return;
  }
  r.heading("Effects ranked by the share of the residual they explain");
  Plot p;
  p.kind = Plot::Kind::bar;
  p.title = "Share of the baseline residual explained (* significant)";
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
  if (!e->rig_block.empty())
    r.paragraph("The fitted effect, for the rig file under `effects:` (rigflex diagnose writes it as effects/" +
                e->effect + ".yaml in its output folder, ready for `rigflex compare --effects`):\n" +
                keep_indentation(e->rig_block));
}

void baseline_section(HtmlReport& r, const diagnose::Diagnosis& d, Eigen::Index channels,
                      const diagnose::ResidualAnalysis* analysis) {
  if (d.baseline.empty()) return;
  r.heading("Baseline: the model as it is");
  history_table(r, d.baseline, channels);
  history_plots(r, d.baseline.front(), diagnose::channel_names(static_cast<int>(channels / 3)), Curves::residual);
  if (analysis) analysis_sections(r, *analysis, sources_of(d.baseline));
}

// ---------------------------------------------------------------- identification

void check_identification(const IdentificationReport& r) {
  for (const auto& a : r.algorithms)
    require(a.records.size() == a.results.size(),
            std::string("identification report: ") + identify::to_string(a.algorithm) + " has " +
                std::to_string(a.results.size()) + " results and " + std::to_string(a.records.size()) + " records");
}

std::string set_name(const IdentificationReport& r, size_t k) {
  return k < r.set_names.size() ? short_source(r.set_names[k]) : "set " + std::to_string(k + 1);
}

// Mean and sample standard deviation; NaN propagates (a non-finite set is shown, not hidden).
std::pair<double, double> mean_sd(const std::vector<double>& x) {
  if (x.empty()) return {kNaN, kNaN};
  double m = 0;
  for (double v : x) m += v / static_cast<double>(x.size());
  if (x.size() < 2) return {m, kNaN};
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return {m, std::sqrt(s / static_cast<double>(x.size() - 1))};
}

// Quantity i (0: mass, 1..9: identify::mass_components) of every set.
std::vector<double> component_of(const std::vector<fe::MassProperties>& sets, size_t i) {
  std::vector<double> v;
  for (const auto& p : sets) v.push_back(quantities_of(p)[i]);
  return v;
}

// The display of every record and the reference of the report.
std::array<Quantity, 10> mass_quantities(const IdentificationReport& rep) {
  std::vector<const fe::MassProperties*> shown;
  for (const auto& a : rep.algorithms)
    for (const auto& p : a.records) shown.push_back(&p);
  if (rep.reference) shown.push_back(&*rep.reference);
  return mass_quantities(shown);
}

void identification_overview(HtmlReport& r, const IdentificationReport& rep) {
  const char* constraint = rep.options.cog_constraint == identify::CogConstraint::none       ? "none"
                           : rep.options.cog_constraint == identify::CogConstraint::in_plane ? "in plane (xG, yG imposed)"
                                                                                      : "full (CoG imposed)";
  std::vector<std::string> names;
  for (size_t k = 0; k < rep.set_names.size(); ++k) names.push_back(set_name(rep, k));
  r.heading("Overview");
  r.paragraph(std::string(rep.tare ? "Body (tare subtracted)" : "System on the rods (carrying frame + body)") +
              ", " + std::to_string(rep.set_names.size()) + " measurement set(s): " + joined(names, "none") +
              ".\nSavitzky-Golay window " + fmt("%.3g", rep.options.differentiation.window_s) + " s, degree " +
              std::to_string(rep.options.differentiation.degree) + "; " + fmt("%.3g", rep.options.equation_rate_hz) +
              " equation times per second; CoG constraint: " + constraint + "." +
              (rep.reference ? "" : "\nNo reference given.") +
              (rep.static_cog_height ? "\nStatic zG: " + fmt("%.2f", 1e3 * *rep.static_cog_height) + " mm." : ""));
}

void sets_table(HtmlReport& r, const IdentificationReport& rep, const IdentificationReport::Algorithm& a) {
  const auto q = mass_quantities(rep);
  Table t{{"set"}, {}};
  for (const auto& c : q) t.header.push_back(c.name);
  t.header.insert(t.header.end(), {"condition", "equations", "positive definite", "triangle inequality"});
  for (size_t k = 0; k < a.records.size(); ++k) {
    std::vector<std::string> row{set_name(rep, k)};
    const auto c = quantities_of(a.records[k]);
    for (size_t i = 0; i < 10; ++i) row.push_back(q[i](c[i]));
    const identify::IdentificationResult& res = a.results[k];
    row.insert(row.end(), {fmt("%.3g", res.condition_number), std::to_string(res.equations),
                           yes_no(res.positive_definite), yes_no(res.triangle_inequality)});
    t.rows.push_back(row);
  }
  for (const bool sd : {false, true}) {
    if (sd && a.records.size() < 2) break;
    std::vector<std::string> row{sd ? "std" : "mean"};
    for (size_t i = 0; i < 10; ++i) {
      const auto [m, s] = mean_sd(component_of(a.records, i));
      row.push_back(q[i](sd ? s : m));
    }
    row.insert(row.end(), {"", "", "", ""});
    t.rows.push_back(row);
  }
  r.table(t, std::string(identify::to_string(a.algorithm)) + " algorithm, per set");
}

void mean_vs_reference_table(HtmlReport& r, const IdentificationReport& rep) {
  Table t{{"quantity"}, {}};
  for (const auto& a : rep.algorithms) t.header.push_back(std::string(identify::to_string(a.algorithm)) + " mean ± std");
  if (rep.reference) {
    t.header.push_back("reference");
    for (const auto& a : rep.algorithms) t.header.push_back(std::string(identify::to_string(a.algorithm)) + " − reference");
  }
  const auto q = mass_quantities(rep);
  for (size_t i = 0; i < 10; ++i) {
    const double ref = rep.reference ? quantities_of(*rep.reference)[i] : kNaN;
    std::vector<std::string> row{q[i].name};
    std::vector<double> means;
    for (const auto& a : rep.algorithms) {
      const auto [m, s] = mean_sd(component_of(a.records, i));
      row.push_back(q[i](m, s));
      means.push_back(m);
    }
    if (rep.reference) {
      row.push_back(q[i](ref));
      for (double m : means) row.push_back(q[i](m - ref));
    }
    t.rows.push_back(row);
  }
  r.heading("Mass properties" + std::string(rep.reference ? " against the reference" : ""));
  r.table(t, "Mean over the sets (std over the sets); inertia about the CoG, products as negative integrals");
}

void accuracy_table(HtmlReport& r, const IdentificationReport& rep) {
  if (!rep.reference) return;
  Table t{{"component"}, {}};
  std::vector<identify::AccuracyShare> shares;
  for (const auto& a : rep.algorithms) {
    if (a.records.empty()) continue;
    t.header.push_back(identify::to_string(a.algorithm));
    shares.push_back(identify::share_within_accuracy(a.records, *rep.reference, rep.limits));
  }
  if (shares.empty()) return;
  r.heading("Accuracy against the reference");
  for (size_t i = 0; i <= 9; ++i) {
    std::vector<std::string> row{i < 9 ? identify::mass_component_names()[i] : "all nine"};
    for (const auto& s : shares) row.push_back(percent(i < 9 ? s.component[i] : s.all));
    t.rows.push_back(row);
  }
  r.table(t, "Share of the sets inside the rig's accuracy (CoG " + fmt("%.1f", 1e3 * rep.limits.cog_in_plane_m) +
                 " mm in plane, " + fmt("%.1f", 1e3 * rep.limits.cog_height_m) + " mm in height; moments " +
                 percent(rep.limits.moment_relative) + "; products " + percent(rep.limits.product_of_largest) +
                 " of the largest moment)");
}

bool all_finite(const std::vector<fe::MassProperties>& sets) {
  for (const auto& p : sets)
    for (double v : identify::mass_components(p))
      if (!std::isfinite(v)) return false;
  return true;
}

void welch_table(HtmlReport& r, const IdentificationReport& rep) {
  if (rep.algorithms.size() != 2) return;
  const auto& a = rep.algorithms[0].records;
  const auto& b = rep.algorithms[1].records;
  if (a.size() < 2 || b.size() < 2) return;
  r.heading("Rigid against flexible");
  if (!all_finite(a) || !all_finite(b)) {
    r.paragraph("Not tested (non-finite identified values).");
    return;
  }
  const auto tests = identify::compare_algorithms(a, b);
  Table t{{"component", "t", "degrees of freedom", "p-value", "significant"}, {}};
  for (size_t i = 0; i < 9; ++i)
    t.rows.push_back({identify::mass_component_names()[i], fmt("%+.3g", tests[i].t), fmt("%.3g", tests[i].degrees_of_freedom),
                      fmt("%.3g", tests[i].p_value), yes_no(tests[i].significant)});
  r.table(t, std::string(identify::to_string(rep.algorithms[0].algorithm)) + " against " +
                 identify::to_string(rep.algorithms[1].algorithm) + ": Welch t, two-sided, alpha 0.05");
}

// What the CoG heights are compared with, as identification.json does: the
// static zG (tare taken out of it when the records are the body's), else the
// reference's; none when the constraint imposes zG.
struct HeightReference {
  std::optional<double> z;
  std::string what;
};
HeightReference height_reference(const IdentificationReport& rep, const IdentificationReport::Algorithm& a) {
  if (rep.static_cog_height) {
    double z = *rep.static_cog_height;
    if (rep.tare && !a.results.empty()) {
      const double m = a.results.front().properties.mass;
      z = (m * z - rep.tare->mass * rep.tare->cog.z()) / (m - rep.tare->mass);
    }
    return {z, "static zG"};
  }
  if (rep.reference) return {rep.reference->cog.z(), "reference zG"};
  return {std::nullopt, "mean zG"};
}

// The algorithm's points and their normal line (mean, std of the values).
void probability_series(Plot& p, const std::string& label, std::vector<double> dz) {
  std::erase_if(dz, [](double v) { return !std::isfinite(v); });
  if (dz.empty()) return;
  PlotSeries pts{label, {}, {}, true, {}};
  for (const auto& q : identify::normal_probability(dz)) {
    pts.x.push_back(q.value);
    pts.y.push_back(q.quantile);
  }
  p.series.push_back(pts);
  const auto [m, s] = mean_sd(dz);
  if (!(s > 0)) return;
  const double lo = pts.x.front(), hi = pts.x.back();
  p.series.push_back({"normal line", {lo, hi}, {(lo - m) / s, (hi - m) / s}, false, kDash});
}

// One algorithm's plot; none when no set has a finite height.
void normal_probability_plot(HtmlReport& r, const IdentificationReport& rep, const IdentificationReport::Algorithm& a) {
  const HeightReference ref = height_reference(rep, a);
  std::vector<double> z = component_of(a.records, 3);  // zG
  std::vector<double> finite = z;
  std::erase_if(finite, [](double v) { return !std::isfinite(v); });
  const double base = ref.z ? *ref.z : mean_sd(finite).first;
  for (double& v : z) v = 1e3 * (v - base);
  Plot p;
  p.title = std::string(identify::to_string(a.algorithm)) + " algorithm: CoG height against the " + ref.what;
  p.x_label = "zG − " + ref.what + " (mm)";
  p.y_label = "standard normal quantile";
  probability_series(p, "sets", z);
  if (!p.series.empty()) r.plot(p);
}

void normal_probability_section(HtmlReport& r, const IdentificationReport& rep) {
  r.heading("CoG height: normal probability");
  if (rep.options.cog_constraint == identify::CogConstraint::full) {
    r.paragraph("The CoG is imposed by the static procedure: its height has no scatter to plot.");
    return;
  }
  const std::string what = rep.algorithms.empty() ? "" : height_reference(rep, rep.algorithms.front()).what;
  r.paragraph("Per set the identified zG minus the " + what +
              ", against the standard-normal quantile of its rank (Blom positions). Points along the dashed line "
              "(mean and standard deviation of the sets): the set-to-set scatter is normal; the line's offset "
              "from 0 is the bias.");
  const int before = r.plot_count();
  for (const auto& a : rep.algorithms) normal_probability_plot(r, rep, a);
  if (r.plot_count() == before) r.paragraph("No set has a finite CoG height.");
}

// ---------------------------------------------------------------- sweep

double median(std::vector<double> v) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

using ErrorOf = double (*)(const identify::ErrorSummary&);
double zg_error_mm(const identify::ErrorSummary& e) { return 1e3 * e.zG_mean_m; }
double jyy_error_percent(const identify::ErrorSummary& e) { return 100 * e.moment_mean[1]; }

// One curve: the points of one sweep kind with an f1, by f1; none without a finite error.
void sweep_series(Plot& p, const std::vector<identify::SweepPoint>& points, identify::SweepKind kind, bool flexible, ErrorOf error) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& pt : points) {
    if (pt.kind != kind || !pt.f1_hz || !std::isfinite(*pt.f1_hz)) continue;
    const auto& e = flexible ? pt.flexible : pt.rigid;
    xy.push_back({*pt.f1_hz, e ? error(*e) : kNaN});
  }
  if (std::none_of(xy.begin(), xy.end(), [](const auto& v) { return std::isfinite(v.second); })) return;
  std::sort(xy.begin(), xy.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  PlotSeries s{std::string(flexible ? "flexible" : "rigid") + ", " + identify::to_string(kind) + " sweep", {}, {}, false,
               flexible ? kDash : std::vector<double>{}};
  for (const auto& [x, y] : xy) {
    s.x.push_back(x);
    s.y.push_back(y);
  }
  p.series.push_back(s);
}

std::vector<PlotMarker> swing_markers(const std::vector<identify::SweepPoint>& points) {
  std::vector<double> swing;
  for (const auto& p : points) swing.push_back(p.swing_max_hz.value_or(kNaN));
  const double f = median(swing);
  if (!(f > 0)) return {};
  return {{3 * f, "3 × highest swing " + fmt("%.3g Hz", 3 * f)}, {4 * f, "4 × highest swing " + fmt("%.3g Hz", 4 * f)}};
}

void sweep_plot(HtmlReport& r, const std::vector<identify::SweepPoint>& points, const std::string& title,
                const std::string& y_label, ErrorOf error) {
  Plot p;
  p.title = title;
  p.x_label = "first deformation frequency f1 (Hz)";
  p.y_label = y_label;
  p.log_x = true;
  for (const auto kind : {identify::SweepKind::mass, identify::SweepKind::stiffness})
    for (const bool flexible : {false, true}) sweep_series(p, points, kind, flexible, error);
  p.markers = swing_markers(points);
  r.plot(p);
}

void sweep_table(HtmlReport& r, const std::vector<identify::SweepPoint>& points) {
  Table t{{"kind", "scale", "f1 (Hz)", "highest swing (Hz)", "f1 / swing", "rigid zG error (mm)", "rigid Jyy error",
           "flexible zG error (mm)", "flexible Jyy error", "failure"},
          {}};
  auto opt = [](const std::optional<double>& v, const char* f) { return v ? fmt(f, *v) : "–"; };
  auto zg = [](const std::optional<identify::ErrorSummary>& e) {
    return e ? plus_minus(1e3 * e->zG_mean_m, e->sets > 1 ? 1e3 * e->zG_std_m : kNaN, "%.2f") : "–";
  };
  auto jyy = [](const std::optional<identify::ErrorSummary>& e) {
    return e ? plus_minus(100 * e->moment_mean[1], e->sets > 1 ? 100 * e->moment_std[1] : kNaN, "%.3f") + " %" : "–";
  };
  for (const auto& p : points)
    t.rows.push_back({identify::to_string(p.kind), fmt("%.3g", p.scale), opt(p.f1_hz, "%.3f"), opt(p.swing_max_hz, "%.3f"),
                      opt(p.ratio, "%.2f"), zg(p.rigid), jyy(p.rigid), zg(p.flexible), jyy(p.flexible), p.failure});
  r.table(t, "Sweep points (errors: identified − true; mean ± std over the sets)");
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
  baseline_section(r, d, channels, baseline_analysis);
  return r;
}

HtmlReport identification_html(const IdentificationReport& rep) {
  check_identification(rep);
  HtmlReport r("rigflex identify: " + (rep.rig.empty() ? std::string("mass properties") : rep.rig));
  identification_overview(r, rep);
  mean_vs_reference_table(r, rep);
  normal_probability_section(r, rep);
  accuracy_table(r, rep);
  welch_table(r, rep);
  r.heading("Per set");
  for (const auto& a : rep.algorithms) sets_table(r, rep, a);
  return r;
}

HtmlReport sweep_html(const std::string& rig, const std::vector<identify::SweepPoint>& points) {
  HtmlReport r("rigflex sweep: " + (rig.empty() ? std::string("identification error against f1") : rig));
  r.heading("Identification error against the first deformation frequency");
  r.paragraph("Mass scaled (inertia by the same ratio) at nominal stiffness, and the stiffness of frames and rods "
              "scaled at nominal mass; errors of the rigid (solid) and the flexible (dashed) algorithm on virtual "
              "measurements. Identification error grows steeply once f1 falls below 3-4 times the highest swing "
              "frequency (vertical lines).");
  if (std::any_of(points.begin(), points.end(), [](const auto& p) { return p.f1_hz && std::isfinite(*p.f1_hz); })) {
    sweep_plot(r, points, "CoG height error against f1", "zG error, identified − true (mm)", zg_error_mm);
    sweep_plot(r, points, "Jyy error against f1", "Jyy error, relative (%)", jyy_error_percent);
  } else {
    r.paragraph("No point has a deformation frequency (nothing deforms): no error curve to draw.");
  }
  sweep_table(r, points);
  return r;
}

}  // namespace rigflex::report
