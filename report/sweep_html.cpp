// The sweep report.
#include "report/reports.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>

#include "report/report_text.hpp"

namespace rigflex::report {
namespace {

using namespace text;

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
