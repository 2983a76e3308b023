#include "report/html_report.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "io/atomic_file.hpp"

// Generated at build time from third_party/js/node_modules/chart.js/dist/chart.umd.js
// by cmake/embed_text.cmake (see the top-level CMakeLists.txt).
namespace rigflex::report::detail {
extern const unsigned char kChartJs[];
extern const std::size_t kChartJs_size;
}  // namespace rigflex::report::detail

namespace rigflex::report {

namespace {

using nlohmann::json;

// Installed first in <head>: every error the page meets is recorded, so the
// browser test can tell a clean page from a broken one.
constexpr std::string_view kHealthJs = R"js(
window.__reportErrors = [];
window.onerror = function (message, source, line, column, error) {
  window.__reportErrors.push(String(error && error.stack ? error.stack : message) + ' (line ' + line + ')');
};
window.addEventListener('unhandledrejection', function (e) {
  window.__reportErrors.push('unhandled rejection: ' + String(e.reason));
});
(function () {
  var original = console.error;
  console.error = function () {
    window.__reportErrors.push(Array.prototype.map.call(arguments, String).join(' '));
    return original.apply(console, arguments);
  };
})();
)js";

// Draws the plots from the JSON block #report-data into canvas#plot-<i>.
constexpr std::string_view kRenderJs = R"js(
(function () {
  'use strict';
  var palette = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd',
                 '#8c564b', '#e377c2', '#bcbd22', '#17becf', '#393b79'];

  // Vertical lines with labels (plot markers), drawn over the datasets.
  var markerPlugin = {
    id: 'rigflexMarkers',
    afterDatasetsDraw: function (chart, args, options) {
      var markers = options.markers || [];
      var area = chart.chartArea, scale = chart.scales.x, ctx = chart.ctx;
      if (!scale || !markers.length) return;
      ctx.save();
      ctx.lineWidth = 1;
      ctx.font = '11px sans-serif';
      ctx.textBaseline = 'bottom';
      markers.forEach(function (m) {
        var px = scale.getPixelForValue(m.x);
        if (!isFinite(px) || px < area.left - 0.5 || px > area.right + 0.5) {
          // The axis is made to reach every marker (reachMarkers): one off it is a fault.
          console.error('marker "' + m.label + '" at x = ' + m.x + ' lies off the x axis');
          return;
        }
        ctx.strokeStyle = 'rgba(60, 60, 60, 0.8)';
        ctx.setLineDash([5, 4]);
        ctx.beginPath();
        ctx.moveTo(px, area.top);
        ctx.lineTo(px, area.bottom);
        ctx.stroke();
        if (m.label) {  // along the line, on a light box, reading downwards
          ctx.save();
          ctx.translate(px + 2, area.top + 4);
          ctx.rotate(Math.PI / 2);
          ctx.fillStyle = 'rgba(255, 255, 255, 0.85)';
          ctx.fillRect(-2, -13, ctx.measureText(m.label).width + 4, 13);
          ctx.fillStyle = '#222';
          ctx.fillText(m.label, 0, -1);
          ctx.restore();
        }
      });
      ctx.restore();
    }
  };

  // Log axes: labels at 1, 2 and 5 of each decade only, as plain numbers.
  function logTick(v) {
    var m = v / Math.pow(10, Math.floor(Math.log10(v) + 1e-9));
    return [1, 2, 5].some(function (k) { return Math.abs(m - k) < 1e-6; }) ? String(Number(v.toPrecision(6))) : '';
  }

  function axis(type, label, tight) {
    var a = { type: type, title: { display: !!label, text: label } };
    if (type === 'logarithmic') a.ticks = { callback: logTick, autoSkip: true };
    if (tight) a.bounds = 'data';
    return a;
  }

  // The x axis reaches every marker: a marker is a reference the data is
  // read against, so it is drawn on the axis even where no point lies near it.
  function reachMarkers(x, markers, log) {
    var xs = (markers || []).map(function (m) { return m.x; }).filter(isFinite);
    if (!xs.length) return;
    var lo = Math.min.apply(null, xs), hi = Math.max.apply(null, xs);
    var pad = log ? 0 : 0.02 * (hi - lo || Math.abs(hi) || 1);
    x.suggestedMin = log ? lo / 1.05 : lo - pad;
    x.suggestedMax = log ? hi * 1.05 : hi + pad;
  }

  function config(p) {
    var bar = p.kind === 'bar';
    // A line series without a label continues the one before it (a band's
    // second edge): its colour, no legend entry of its own.
    var slot = [], next = 0;
    p.series.forEach(function (s, i) { slot.push(!bar && i > 0 && !s.label ? slot[i - 1] : next++); });
    var datasets = p.series.map(function (s, i) {
      var color = palette[slot[i] % palette.length];
      // Past the palette, lines repeat its colours dashed.
      var dash = s.dash.length || bar || slot[i] < palette.length ? s.dash : [6, 3];
      var d = { label: s.label, borderColor: color, backgroundColor: bar ? color + 'cc' : color,
                borderWidth: bar ? 1 : 1.5, borderDash: dash };
      if (bar) {
        d.data = s.y;
      } else {
        d.data = s.x.map(function (x, k) { return { x: x, y: s.y[k] }; });
        d.showLine = p.kind === 'line' && !s.points;
        d.pointRadius = d.showLine ? 0 : 2.5;
        d.pointHitRadius = 4;
      }
      return d;
    });
    var legend = p.series.length > 1 || p.series.some(function (s) { return s.label; });
    var x = axis(bar ? 'category' : (p.log_x ? 'logarithmic' : 'linear'), p.x_label, p.kind === 'line');
    if (!bar) reachMarkers(x, p.markers, p.log_x);
    return {
      type: bar ? 'bar' : (p.kind === 'scatter' ? 'scatter' : 'line'),
      data: bar ? { labels: p.categories, datasets: datasets } : { datasets: datasets },
      options: {
        animation: false,
        responsive: true,
        maintainAspectRatio: false,
        interaction: { mode: 'nearest', intersect: false },
        scales: {
          x: x,
          y: axis(p.log_y ? 'logarithmic' : 'linear', p.y_label, false)
        },
        plugins: {
          legend: { display: legend, labels: { filter: function (item) { return !!item.text; } } },
          rigflexMarkers: { markers: p.markers }
        }
      },
      plugins: [markerPlugin]
    };
  }

  function hasData(p) {
    return p.series.some(function (s) { return s.y.some(function (v) { return v !== null; }); });
  }

  // Ink in a series colour on the canvas (axes, grid, text and markers are grey).
  function drawn(canvas) {
    if (!canvas.width || !canvas.height) return false;
    var px = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    for (var i = 0; i < px.length; i += 4) {
      if (px[i + 3] === 0) continue;
      if (Math.max(px[i], px[i + 1], px[i + 2]) - Math.min(px[i], px[i + 1], px[i + 2]) > 60) return true;
    }
    return false;
  }

  var plots = [];
  try {
    plots = JSON.parse(document.getElementById('report-data').textContent);
  } catch (e) {
    console.error('report data: ' + e);
  }
  var rendered = 0, blank = [];
  plots.forEach(function (p, i) {
    try {
      var canvas = document.getElementById('plot-' + i);
      new Chart(canvas, config(p));
      // A chart counts as drawn only with data in it (a frame of axes is not a chart).
      if (hasData(p) && drawn(canvas)) rendered++;
      else blank.push(i + 1);
    } catch (e) {
      console.error('plot ' + (i + 1) + ': ' + (e && e.stack ? e.stack : e));
    }
  });
  var errors = window.__reportErrors;
  var list = document.getElementById('report-errors');
  if (errors.length) {
    list.textContent = errors.join('\n');
    list.hidden = false;
  }
  document.body.dataset.plots = String(plots.length);
  document.body.dataset.blankPlots = blank.join(',');
  document.body.dataset.errors = String(errors.length);
  document.body.dataset.plotsRendered = String(rendered);
})();
)js";

constexpr std::string_view kCss = R"css(
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif;
       margin: 0; color: #1a1a1a; background: #fff; }
main { max-width: 1100px; margin: 0 auto; padding: 1.5rem 1.5rem 3rem; }
h1 { font-size: 1.6rem; margin: 0 0 1rem; }
h2 { font-size: 1.25rem; margin: 2rem 0 0.6rem; border-bottom: 1px solid #ddd; padding-bottom: 0.2rem; }
p { white-space: pre-line; line-height: 1.45; }
table { border-collapse: collapse; margin: 0.8rem 0; font-size: 0.9rem; }
caption { caption-side: top; text-align: left; font-weight: 600; padding-bottom: 0.3rem; }
th, td { border: 1px solid #ccc; padding: 0.25rem 0.6rem; text-align: left; white-space: pre-line; }
th { background: #f3f3f3; }
tbody tr:nth-child(even) { background: #fafafa; }
figure.plot { margin: 1rem 0 1.5rem; }
figure.plot figcaption { font-weight: 600; margin-bottom: 0.3rem; }
figure.plot .note { font-weight: normal; color: #666; font-size: 0.85rem; }
.plot-box { position: relative; height: 380px; }
.small-multiples { margin: 1rem 0 1.5rem; }
.small-multiples .caption { font-weight: 600; margin-bottom: 0.3rem; }
.small-multiples .grid { display: grid; gap: 0.4rem 1rem; }
figure.plot.small { margin: 0; }
figure.plot.small figcaption { font-weight: 600; font-size: 0.9rem; margin-bottom: 0; }
figure.plot.small .plot-box { height: 230px; }
#report-errors { color: #a00; white-space: pre-wrap; }
@media print { .plot-box { height: 300px; } figure.plot.small .plot-box { height: 200px; }
               figure.plot, table { break-inside: avoid; } }
)css";

std::string json_text(const json& j) {
  // JSON inside <script>: a '<' only occurs in strings, where \u003c is the
  // same character; so neither "</script" nor "<!--" can end the block early.
  const std::string raw = j.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(raw.size() + 16);
  for (const char c : raw) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

// 7 significant digits: far finer than a pixel, and a short JSON number.
json display_number(double v) {
  if (!std::isfinite(v)) return nullptr;
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 7);
  if (ec != std::errc()) return v;
  double r = v;
  std::from_chars(buf, end, r);
  return r;
}

std::string decimation_note(std::size_t series, std::size_t longest, std::size_t max_points) {
  return "<span class=\"note\">(" + std::to_string(series) + " series of up to " + std::to_string(longest) +
         " points drawn by " + std::to_string(max_points) + ", keeping each interval's minimum and maximum)</span>";
}

std::string plot_name(const Plot& p, int index) {
  return "plot " + std::to_string(index) + (p.title.empty() ? "" : " (\"" + p.title + "\")");
}

std::string series_name(const PlotSeries& s, std::size_t index) {
  return "series " + std::to_string(index + 1) + (s.label.empty() ? "" : " (\"" + s.label + "\")");
}

json number_array(const std::vector<double>& v) {
  json a = json::array();
  a.get_ref<json::array_t&>().reserve(v.size());
  for (const double x : v) a.push_back(display_number(x));
  return a;
}

}  // namespace

std::string escape_html(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string_view chart_js() {
  return {reinterpret_cast<const char*>(detail::kChartJs), detail::kChartJs_size};
}

PlotSeries decimate_min_max(const PlotSeries& s, std::size_t max_points) {
  if (max_points < 8) throw std::invalid_argument("decimate_min_max: max_points must be at least 8");
  if (s.x.size() != s.y.size())
    throw std::invalid_argument("decimate_min_max: " + series_name(s, 0) + " has " + std::to_string(s.x.size()) +
                                " x values and " + std::to_string(s.y.size()) + " y values");
  PlotSeries out = s;
  out.x.clear();
  out.y.clear();
  std::vector<double> xs, ys;
  xs.reserve(s.x.size());
  ys.reserve(s.y.size());
  std::size_t gaps = 0;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!std::isfinite(s.x[i])) continue;
    xs.push_back(s.x[i]);
    ys.push_back(std::isfinite(s.y[i]) ? s.y[i] : std::numeric_limits<double>::quiet_NaN());
    if (!std::isfinite(s.y[i])) ++gaps;
  }
  const std::size_t n = xs.size();
  if (n <= max_points) {
    out.x = std::move(xs);
    out.y = std::move(ys);
    return out;
  }
  // First and last point, then per bucket of the n - 2 inner points its
  // lowest and highest y, and its first gap when it has one: 2 points per
  // bucket plus at most one per gap, or 3 per bucket when gaps are many.
  const std::size_t budget = max_points - 2;
  const std::size_t buckets = budget >= 3 * gaps ? (budget - gaps) / 2 : budget / 3;
  const std::size_t inner = n - 2;
  out.x.reserve(max_points);
  out.y.reserve(max_points);
  auto emit = [&](std::size_t i) {
    out.x.push_back(xs[i]);
    out.y.push_back(ys[i]);
  };
  emit(0);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t begin = 1 + b * inner / buckets, end = 1 + (b + 1) * inner / buckets;
    std::size_t lo = end, hi = end, gap = end;
    for (std::size_t i = begin; i < end; ++i) {
      if (std::isnan(ys[i])) {
        if (gap == end) gap = i;
        continue;
      }
      if (lo == end || ys[i] < ys[lo]) lo = i;
      if (hi == end || ys[i] > ys[hi]) hi = i;
    }
    std::size_t picked[3] = {lo, hi, gap};
    std::sort(picked, picked + 3);
    for (std::size_t k = 0; k < 3; ++k)
      if (picked[k] != end && (k == 0 || picked[k] != picked[k - 1])) emit(picked[k]);
  }
  emit(n - 1);
  return out;
}

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::heading(const std::string& text) { body_ += "<h2>" + escape_html(text) + "</h2>\n"; }

void HtmlReport::paragraph(const std::string& text) { body_ += "<p>" + escape_html(text) + "</p>\n"; }

void HtmlReport::table(const Table& t, const std::string& caption) {
  for (std::size_t r = 0; r < t.rows.size(); ++r)
    if (!t.header.empty() && t.rows[r].size() != t.header.size())
      throw std::invalid_argument("table" + (caption.empty() ? "" : " \"" + caption + "\"") + ": row " +
                                  std::to_string(r + 1) + " has " + std::to_string(t.rows[r].size()) +
                                  " cells, the header " + std::to_string(t.header.size()));
  std::string h = "<table>\n";
  if (!caption.empty()) h += "<caption>" + escape_html(caption) + "</caption>\n";
  if (!t.header.empty()) {
    h += "<thead><tr>";
    for (const auto& c : t.header) h += "<th>" + escape_html(c) + "</th>";
    h += "</tr></thead>\n";
  }
  h += "<tbody>\n";
  for (const auto& row : t.rows) {
    h += "<tr>";
    for (const auto& c : row) h += "<td>" + escape_html(c) + "</td>";
    h += "</tr>\n";
  }
  h += "</tbody>\n</table>\n";
  body_ += h;
}

void HtmlReport::plot(const Plot& p) {
  const Figure f = figure(p, "plot");
  std::string h = "<figure class=\"plot\">\n<figcaption>" + escape_html(p.title);
  if (f.decimated > 0) h += " " + decimation_note(f.decimated, f.longest, p.max_points);
  body_ += h + "</figcaption>\n" + f.canvas + "</figure>\n";
}

void HtmlReport::small_multiples(const std::vector<Plot>& plots, int columns, const std::string& caption) {
  if (columns < 1) throw std::invalid_argument("small multiples \"" + caption + "\": columns must be at least 1");
  if (plots.empty()) return;
  std::string cells;
  std::size_t decimated = 0, longest = 0, max_points = 0;
  const std::size_t before = plot_data_.size();
  for (const Plot& p : plots) {
    Figure f;
    try {
      f = figure(p, "small plot");
    } catch (...) {
      plot_data_.resize(before);  // all of the grid or none of it
      throw;
    }
    cells += "<figure class=\"plot small\">\n<figcaption>" + escape_html(p.title) + "</figcaption>\n" + f.canvas +
             "</figure>\n";
    decimated += f.decimated;
    longest = std::max(longest, f.longest);
    if (f.decimated > 0) max_points = std::max(max_points, p.max_points);  // what the note says they were drawn by
  }
  std::string h = "<section class=\"small-multiples\">\n<div class=\"caption\">" + escape_html(caption);
  if (decimated > 0) h += " " + decimation_note(decimated, longest, max_points);
  h += "</div>\n<div class=\"grid\" style=\"grid-template-columns: repeat(" + std::to_string(columns) +
       ", minmax(0, 1fr))\">\n" + cells + "</div>\n</section>\n";
  body_ += h;
}

HtmlReport::Figure HtmlReport::figure(const Plot& p, const char* what) {
  const int index = plot_count();
  const std::string name = plot_name(p, index + 1);
  const bool bar = p.kind == Plot::Kind::bar;
  if (p.max_points < 8) throw std::invalid_argument(name + ": max_points must be at least 8");
  if (bar && p.log_x) throw std::invalid_argument(name + ": a bar chart cannot have a logarithmic x axis");

  json series = json::array();
  std::size_t decimated = 0, longest = 0;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const PlotSeries& s = p.series[k];
    json js = {{"label", s.label}, {"points", s.points}, {"dash", s.dash}};
    if (bar) {
      if (s.y.size() != p.categories.size())
        throw std::invalid_argument(name + ", " + series_name(s, k) + ": " + std::to_string(s.y.size()) +
                                    " values for " + std::to_string(p.categories.size()) + " categories");
      std::vector<double> y = s.y;
      if (p.log_y)
        for (double& v : y)
          if (!(v > 0)) v = std::numeric_limits<double>::quiet_NaN();
      js["y"] = number_array(y);
    } else {
      if (s.x.size() != s.y.size())
        throw std::invalid_argument(name + ", " + series_name(s, k) + ": " + std::to_string(s.x.size()) +
                                    " x values and " + std::to_string(s.y.size()) + " y values");
      PlotSeries clean = s;
      constexpr double nan = std::numeric_limits<double>::quiet_NaN();
      for (std::size_t i = 0; i < clean.x.size(); ++i) {
        if (p.log_x && !(clean.x[i] > 0)) clean.x[i] = nan;  // dropped
        if (p.log_y && !(clean.y[i] > 0)) clean.y[i] = nan;  // a gap
      }
      const auto placed = static_cast<std::size_t>(
          std::count_if(clean.x.begin(), clean.x.end(), [](double x) { return std::isfinite(x); }));
      clean = decimate_min_max(clean, p.max_points);
      if (placed > p.max_points) {
        ++decimated;
        longest = std::max(longest, placed);
      }
      js["x"] = number_array(clean.x);
      js["y"] = number_array(clean.y);
    }
    series.push_back(std::move(js));
  }
  json markers = json::array();
  if (!bar)
    for (const auto& m : p.markers)
      if (std::isfinite(m.x) && (!p.log_x || m.x > 0)) markers.push_back({{"x", display_number(m.x)}, {"label", m.label}});

  static constexpr const char* kinds[] = {"line", "scatter", "bar"};
  const json data = {{"kind", kinds[static_cast<int>(p.kind)]},
                     {"title", p.title},
                     {"x_label", p.x_label},
                     {"y_label", p.y_label},
                     {"log_x", p.log_x},
                     {"log_y", p.log_y},
                     {"categories", bar ? json(p.categories) : json::array()},
                     {"series", std::move(series)},
                     {"markers", std::move(markers)}};
  plot_data_.push_back(json_text(data));
  Figure f;
  f.canvas = "<div class=\"plot-box\"><canvas id=\"plot-" + std::to_string(index) + "\" role=\"img\" aria-label=\"" +
             escape_html(p.title.empty() ? what : p.title) + "\"></canvas></div>\n";
  f.decimated = decimated;
  f.longest = longest;
  return f;
}

int HtmlReport::plot_count() const { return static_cast<int>(plot_data_.size()); }

std::string HtmlReport::html() const {
  std::string_view library = chart_js();
  // The bundle ends with a source-map comment; the map is not shipped.
  if (const auto at = library.rfind("//# sourceMappingURL="); at != std::string_view::npos)
    library = library.substr(0, at);

  std::size_t data_size = 0;
  for (const auto& d : plot_data_) data_size += d.size() + 2;
  std::string h;
  h.reserve(library.size() + body_.size() + data_size + 8192);
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
       "<meta name=\"generator\" content=\"rigflex\">\n<title>";
  h += escape_html(title_);
  h += "</title>\n<style>";
  h += kCss;
  h += "</style>\n<script>";
  h += kHealthJs;
  h += "</script>\n<script>\n";
  h += library;
  h += "\n</script>\n</head>\n<body>\n<main>\n<h1>";
  h += escape_html(title_);
  h += "</h1>\n";
  h += body_;
  h += "<pre id=\"report-errors\" hidden></pre>\n</main>\n<script type=\"application/json\" id=\"report-data\">[";
  for (std::size_t i = 0; i < plot_data_.size(); ++i) {
    if (i > 0) h += ",\n";
    h += plot_data_[i];
  }
  h += "]</script>\n<script>";
  h += kRenderJs;
  h += "</script>\n</body>\n</html>\n";
  return h;
}

void HtmlReport::write(const std::filesystem::path& file) const {
  const std::string text = html();
  try {
    io::write_text_atomically(file, text);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write the HTML report " + file.string() + ": " + e.what());
  }
}

}  // namespace rigflex::report
