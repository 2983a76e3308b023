// The identify report.
#include "report/reports.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>

#include "identify/identification_rig.hpp"
#include "identify/mass_statistics.hpp"
#include "report/report_text.hpp"

namespace rigflex::report {
namespace {

using namespace text;

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
  return text::mass_quantities(shown);
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
  // Where each ranked point of a normal sample of this size lies with 2-sigma
  // probability: the line alone cannot say whether a point is far from it.
  PlotSeries below{"2σ band", {}, {}, false, kDot}, above{"", {}, {}, false, kDot};
  const auto band = identify::normal_order_statistic_band(pts.y.size(), 2.0);
  for (std::size_t i = 0; i < band.size(); ++i) {
    below.x.push_back(m + s * band[i].lower);
    above.x.push_back(m + s * band[i].upper);
    below.y.push_back(pts.y[i]);
    above.y.push_back(pts.y[i]);
  }
  p.series.push_back(below);
  p.series.push_back(above);
}

// One algorithm's plot; none when no set has a finite height.
void normal_probability_plot(HtmlReport& r, const IdentificationReport& rep, const IdentificationReport::Algorithm& a) {
  const HeightReference ref = height_reference(rep, a);
  const HeightSample sample = height_sample(a);
  std::vector<double> z = sample.z;
  const double base = ref.z ? *ref.z : mean_sd(z).first;
  for (double& v : z) v = 1e3 * (v - base);
  Plot p;
  p.title = std::string(identify::to_string(a.algorithm)) + " algorithm: CoG height against the " + ref.what;
  p.x_label = "zG − " + ref.what + " (mm)";
  p.y_label = "standard normal quantile (σ)";
  const bool tests = sample.of == "tests";
  probability_series(p, tests ? "tests (each history alone)" : "sets", z);
  if (tests) {  // the sets' own result: all of a set's histories in one solve
    std::vector<double> sets = component_of(a.records, 3);
    std::erase_if(sets, [](double v) { return !std::isfinite(v); });
    if (!sets.empty()) {
      const double m = 1e3 * (mean_sd(sets).first - base);
      p.markers.push_back({m, sets.size() == 1 ? "the set, all histories: " + fixed(m, 2) + " mm"
                                               : "mean of the sets: " + fixed(m, 2) + " mm"});
    }
  }
  if (!p.series.empty()) r.plot(p);
}

void normal_probability_section(HtmlReport& r, const IdentificationReport& rep) {
  r.heading("CoG height: normal probability");
  if (rep.options.cog_constraint == identify::CogConstraint::full) {
    r.paragraph("The CoG is imposed by the static procedure: its height has no scatter to plot.");
    return;
  }
  const std::string what = rep.algorithms.empty() ? "" : height_reference(rep, rep.algorithms.front()).what;
  r.paragraph(
      "Per test (each history identified alone; per set where the sets hold one history each) the "
      "identified zG minus the " +
      what +
      ", against the standard-normal quantile of its rank (Blom positions). Points along the dashed line "
      "(their mean and standard deviation): the scatter is normal; the line's offset from 0 is the bias. "
      "The dotted band holds each ranked point of a normal sample this size with 2σ (95.45 %) probability: "
      "a point outside it is an outlier, or the scatter is not normal. Where tests are plotted, the vertical "
      "line is the sets' own result (all of a set's histories in one solve).");
  const int before = r.plot_count();
  for (const auto& a : rep.algorithms) normal_probability_plot(r, rep, a);
  if (r.plot_count() == before) r.paragraph("No set has a finite CoG height.");
}

}  // namespace

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

}  // namespace rigflex::report
