// The HTML report: text is escaped, the document needs nothing outside itself,
// plot data survive NaN and infinities as JSON, long series are decimated
// keeping their extremes, and the file is written whole or not at all.
// (Rendering in a browser: tests/browser/check_report.sh.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "report/html_report.hpp"
#include "support/temp_files.hpp"

namespace rigflex {
namespace {

namespace fs = std::filesystem;
using report::HtmlReport;
using report::Plot;
using report::PlotSeries;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

// The document without the inlined library (tested on its own).
std::string without_library(const HtmlReport& r) {
  std::string h = r.html();
  const std::string_view lib = report::chart_js();
  const auto at = h.find(lib.substr(0, 200));
  EXPECT_NE(at, std::string::npos);
  const auto end = h.find("</script>", at);
  h.erase(at, end - at);
  return h;
}

// The JSON of the plots, from the <script type="application/json"> block.
nlohmann::json plot_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"report-data\">";
  const auto begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const auto end = html.find("</script>", begin);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

Plot line_plot(std::string title, std::vector<double> x, std::vector<double> y) {
  Plot p;
  p.title = std::move(title);
  p.series.push_back({"s", std::move(x), std::move(y), false, {}});
  return p;
}

TEST(HtmlReport, EscapesTextEverywhere) {
  HtmlReport r("T <title> & \"q\"");
  r.heading("<h2>&");
  r.paragraph("<script>alert('x')</script>");
  r.table({{"<th>"}, {{"a & b"}, {"</td>"}}}, "<caption>");
  Plot p = line_plot("</script><!-- <script>", {1, 2}, {3, 4});
  p.x_label = "</script>";
  p.series[0].label = "</SCRIPT>";
  p.markers = {{1.5, "</script> marker"}};
  r.plot(p);
  const std::string h = without_library(r);

  EXPECT_NE(h.find("<title>T &lt;title&gt; &amp; &quot;q&quot;</title>"), std::string::npos);
  EXPECT_NE(h.find("<h2>&lt;h2&gt;&amp;</h2>"), std::string::npos);
  EXPECT_NE(h.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(h.find("<th>&lt;th&gt;</th>"), std::string::npos);
  EXPECT_NE(h.find("<td>&lt;/td&gt;</td>"), std::string::npos);
  EXPECT_NE(h.find("<caption>&lt;caption&gt;</caption>"), std::string::npos);
  EXPECT_EQ(h.find("<script>alert"), std::string::npos);
  // Every <script> the page opens is closed by its own </script>: none leaks
  // out of the data (the four blocks: health, library, data, rendering).
  EXPECT_EQ(count(h, "<script"), 4u);
  EXPECT_EQ(count(h, "</script>"), 4u);
  EXPECT_EQ(count(h, "<!--"), 0u);
  // The data still read back exactly.
  const auto data = plot_data(h);
  EXPECT_EQ(data[0]["title"], "</script><!-- <script>");
  EXPECT_EQ(data[0]["series"][0]["label"], "</SCRIPT>");
  EXPECT_EQ(data[0]["markers"][0]["label"], "</script> marker");
}

TEST(HtmlReport, InvalidUtf8DoesNotThrow) {
  HtmlReport r("bad \xff utf-8");
  r.plot(line_plot("bad \xc3 title", {1}, {2}));
  EXPECT_NO_THROW(plot_data(r.html()));
}

TEST(HtmlReport, InlinedLibraryCannotEndItsScriptBlock) {
  const std::string_view lib = report::chart_js();
  ASSERT_GT(lib.size(), 100'000u);
  EXPECT_NE(lib.find("Chart.js v4"), std::string_view::npos);
  EXPECT_NE(lib.find("MIT"), std::string_view::npos);
  std::string lower(lib);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  EXPECT_EQ(lower.find("</script"), std::string::npos);
  EXPECT_EQ(lower.find("<!--"), std::string::npos);
}

TEST(HtmlReport, NeedsNoExternalResources) {
  HtmlReport r("offline");
  r.paragraph("text");
  r.plot(line_plot("p", {1, 2, 3}, {1, 4, 9}));
  const std::string full = r.html();
  for (const char* s : {"src=", "<link", "<iframe", "<img", "@import", "url(", "sourceMappingURL"})
    EXPECT_EQ(full.find(s), std::string::npos) << s;
  // URLs appear only in the library's licence comment.
  const std::string h = without_library(r);
  EXPECT_EQ(h.find("http://"), std::string::npos);
  EXPECT_EQ(h.find("https://"), std::string::npos);
  EXPECT_EQ(h.find("//cdn"), std::string::npos);
  // The library is inlined once, whole (but for its source-map comment).
  EXPECT_EQ(count(full, "Chart.js v4"), 1u);
  EXPECT_NE(full.find(report::chart_js().substr(0, report::chart_js().rfind("//# sourceMappingURL="))), std::string::npos);
}

TEST(HtmlReport, CountsPlotsAndCanvases) {
  HtmlReport r("count");
  EXPECT_EQ(r.plot_count(), 0);
  r.plot(line_plot("a", {1, 2}, {1, 2}));
  Plot bar;
  bar.kind = Plot::Kind::bar;
  bar.categories = {"x", "y"};
  bar.series = {{"b", {}, {1, 2}, false, {}}};
  r.plot(bar);
  Plot sc = line_plot("c", {1, 2}, {2, 1});
  sc.kind = Plot::Kind::scatter;
  r.plot(sc);
  EXPECT_EQ(r.plot_count(), 3);
  const std::string h = r.html();
  EXPECT_EQ(count(h, "<canvas id=\"plot-"), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NE(h.find("<canvas id=\"plot-" + std::to_string(i) + "\""), std::string::npos);
  const auto data = plot_data(h);
  ASSERT_EQ(data.size(), 3u);
  EXPECT_EQ(data[0]["kind"], "line");
  EXPECT_EQ(data[1]["kind"], "bar");
  EXPECT_EQ(data[1]["categories"], nlohmann::json::array({"x", "y"}));
  EXPECT_EQ(data[2]["kind"], "scatter");
  // Health hooks and the markers the browser test reads.
  EXPECT_NE(h.find("window.__reportErrors"), std::string::npos);
  EXPECT_NE(h.find("dataset.plotsRendered"), std::string::npos);
  EXPECT_NE(h.find("animation: false"), std::string::npos);
}

TEST(HtmlReport, SmallMultiplesAreAGridOfPlotsAllOrNone) {
  HtmlReport r("grid");
  r.plot(line_plot("before", {1, 2}, {3, 4}));
  std::vector<Plot> cells;
  for (const char* name : {"F1", "F2", "F3", "F4"}) cells.push_back(line_plot(name, {0, 1, 2}, {1, 2, 3}));
  cells[1].max_points = 8;
  cells[1].series[0].x.assign(100, 0.0);
  cells[1].series[0].y.assign(100, 1.0);
  for (int i = 0; i < 100; ++i) cells[1].series[0].x[i] = i;
  r.small_multiples(cells, 2, "<forces> per rod");
  EXPECT_EQ(r.plot_count(), 5);
  const std::string h = without_library(r);
  EXPECT_EQ(count(h, "<canvas id=\"plot-"), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_NE(h.find("<canvas id=\"plot-" + std::to_string(i) + "\""), std::string::npos);
  EXPECT_EQ(count(h, "<figure class=\"plot small\">"), 4u);
  EXPECT_NE(h.find("grid-template-columns: repeat(2, minmax(0, 1fr))"), std::string::npos);
  EXPECT_NE(h.find("&lt;forces&gt; per rod <span class=\"note\">(1 series of up to 100 points drawn by 8"),
            std::string::npos);
  const nlohmann::json data = plot_data(h);
  ASSERT_EQ(data.size(), 5u);
  EXPECT_EQ(data[1]["title"], "F1");
  EXPECT_EQ(data[4]["title"], "F4");

  // A plot that does not fit leaves nothing of the grid behind.
  cells[2].series[0].y.pop_back();
  EXPECT_THROW(r.small_multiples(cells, 2, "broken"), std::invalid_argument);
  EXPECT_EQ(r.plot_count(), 5);
  EXPECT_EQ(plot_data(without_library(r)).size(), 5u);
  EXPECT_EQ(without_library(r).find("broken"), std::string::npos);
  EXPECT_THROW(r.small_multiples(cells, 0, "none"), std::invalid_argument);
  r.small_multiples({}, 3, "empty");  // nothing to draw: nothing written
  EXPECT_EQ(without_library(r).find("empty"), std::string::npos);
}

TEST(HtmlReport, NonFiniteNumbersBecomeNullNotBrokenJson) {
  HtmlReport r("nan");
  Plot p = line_plot("nan", {0, 1, 2, nan, 4, 5}, {1, nan, inf, 3, -inf, 2});
  p.markers = {{nan, "dropped"}, {inf, "dropped"}, {2.5, "kept"}};
  r.plot(p);
  Plot logp = line_plot("log", {-1, 0, 1, 2, 3}, {5, 5, 0, -2, 7});
  logp.log_x = logp.log_y = true;
  logp.markers = {{0, "dropped"}, {2, "kept"}};
  r.plot(logp);
  Plot bar;
  bar.kind = Plot::Kind::bar;
  bar.categories = {"a", "b"};
  bar.series = {{"b", {}, {nan, 1}, false, {}}};
  r.plot(bar);
  const std::string h = r.html();
  const std::string body = h.substr(h.find("</head>"));
  EXPECT_EQ(body.find("NaN"), std::string::npos);
  EXPECT_EQ(body.find("Infinity"), std::string::npos);
  const auto data = plot_data(h);  // parses: valid JSON
  const auto& s = data[0]["series"][0];
  EXPECT_EQ(s["x"], nlohmann::json::parse("[0,1,2,4,5]"));  // the point without x dropped
  EXPECT_EQ(s["y"], nlohmann::json::parse("[1,null,null,null,2]"));
  ASSERT_EQ(data[0]["markers"].size(), 1u);
  EXPECT_EQ(data[0]["markers"][0]["label"], "kept");
  // Log axes: x <= 0 dropped, y <= 0 a gap; markers at x <= 0 dropped.
  EXPECT_EQ(data[1]["series"][0]["x"], nlohmann::json::parse("[1,2,3]"));
  EXPECT_EQ(data[1]["series"][0]["y"], nlohmann::json::parse("[null,null,7]"));
  ASSERT_EQ(data[1]["markers"].size(), 1u);
  EXPECT_EQ(data[2]["series"][0]["y"], nlohmann::json::parse("[null,1]"));
}

TEST(HtmlReport, NumbersKeepSevenSignificantDigits) {
  HtmlReport r("digits");
  r.plot(line_plot("d", {0.1, 1234.5678901}, {1.0 / 3.0, -2.5e-12}));
  const auto s = plot_data(r.html())[0]["series"][0];
  EXPECT_EQ(s["x"][0].get<double>(), 0.1);
  EXPECT_EQ(s["x"][1].get<double>(), 1234.568);
  EXPECT_EQ(s["y"][0].get<double>(), 0.3333333);
  EXPECT_EQ(s["y"][1].get<double>(), -2.5e-12);
}

TEST(HtmlReport, RejectsDataThatDoNotFitThePlot) {
  HtmlReport r("bad");
  Plot p = line_plot("mismatch", {1, 2, 3}, {1, 2});
  p.series[0].label = "F1";
  try {
    r.plot(p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mismatch"), std::string::npos) << what;
    EXPECT_NE(what.find("F1"), std::string::npos) << what;
  }
  Plot bar;
  bar.kind = Plot::Kind::bar;
  bar.categories = {"a", "b"};
  bar.series = {{"b", {}, {1}, false, {}}};
  EXPECT_THROW(r.plot(bar), std::invalid_argument);
  bar.series[0].y = {1, 2};
  bar.log_x = true;
  EXPECT_THROW(r.plot(bar), std::invalid_argument);
  Plot few = line_plot("few", {1}, {1});
  few.max_points = 7;
  EXPECT_THROW(r.plot(few), std::invalid_argument);
  EXPECT_THROW(r.table({{"a", "b"}, {{"1"}}}), std::invalid_argument);
  EXPECT_EQ(r.plot_count(), 0);
}

TEST(HtmlReport, DecimationKeepsExtremesEndsAndGaps) {
  PlotSeries s;
  s.label = "long";
  const int n = 7500;
  for (int i = 0; i < n; ++i) {
    s.x.push_back(i * 0.002);
    s.y.push_back(std::sin(i * 0.01) + 0.001 * (i % 7));
  }
  s.y[1234] = 17.0;   // a spike
  s.y[4321] = -9.0;   // a dip
  s.y[6000] = nan;    // a gap
  s.y[n - 1] = 0.5;
  const PlotSeries d = report::decimate_min_max(s, 4000);
  EXPECT_LE(d.x.size(), 4000u);
  EXPECT_GE(d.x.size(), 3990u);  // the budget used, the single gap costs one point
  ASSERT_EQ(d.x.size(), d.y.size());
  EXPECT_EQ(d.label, "long");
  EXPECT_EQ(d.x.front(), s.x.front());
  EXPECT_EQ(d.y.front(), s.y.front());
  EXPECT_EQ(d.x.back(), s.x.back());
  EXPECT_EQ(d.y.back(), 0.5);
  EXPECT_TRUE(std::is_sorted(d.x.begin(), d.x.end()));
  double lo = inf, hi = -inf;
  int gaps = 0;
  for (const double y : d.y) {
    if (std::isnan(y)) {
      ++gaps;
      continue;
    }
    lo = std::min(lo, y);
    hi = std::max(hi, y);
  }
  EXPECT_EQ(hi, 17.0);
  EXPECT_EQ(lo, -9.0);
  EXPECT_EQ(gaps, 1);
  // Every bucket's extremes: over any window the decimated envelope matches
  // the original's, to the change of the signal within a bucket (4 samples).
  for (int w = 0; w < 10; ++w) {
    const double x0 = w * 1.5, x1 = x0 + 1.5;
    double olo = inf, ohi = -inf, dlo = inf, dhi = -inf;
    for (int i = 0; i < n; ++i)
      if (s.x[i] >= x0 && s.x[i] < x1 && !std::isnan(s.y[i])) olo = std::min(olo, s.y[i]), ohi = std::max(ohi, s.y[i]);
    for (std::size_t i = 0; i < d.x.size(); ++i)
      if (d.x[i] >= x0 && d.x[i] < x1 && !std::isnan(d.y[i])) dlo = std::min(dlo, d.y[i]), dhi = std::max(dhi, d.y[i]);
    EXPECT_GE(dlo, olo) << w;
    EXPECT_LE(dhi, ohi) << w;
    EXPECT_NEAR(dlo, olo, 0.05) << w;
    EXPECT_NEAR(dhi, ohi, 0.05) << w;
  }
  // Many gaps: at most 3 points per bucket, still within the budget.
  PlotSeries holes = s;
  for (int i = 0; i < n; i += 5) holes.y[i] = nan;
  const PlotSeries dh = report::decimate_min_max(holes, 4000);
  EXPECT_LE(dh.x.size(), 4000u);
  EXPECT_GT(std::count_if(dh.y.begin(), dh.y.end(), [](double y) { return std::isnan(y); }), 1000);
  // Short series pass unchanged; bad max_points refused.
  PlotSeries small{"s", {1, 2, 3}, {3, 2, 1}, false, {}};
  const PlotSeries same = report::decimate_min_max(small, 8);
  EXPECT_EQ(same.x, small.x);
  EXPECT_EQ(same.y, small.y);
  EXPECT_THROW(report::decimate_min_max(small, 7), std::invalid_argument);
}

TEST(HtmlReport, LargeReportStaysAFewMegabytes) {
  // 6 histories x 12 channels x 7500 samples (15 s at 500 Hz).
  HtmlReport r("large");
  for (int h = 0; h < 6; ++h) {
    Plot p;
    p.title = "h" + std::to_string(h);
    for (int c = 0; c < 12; ++c) {
      PlotSeries s;
      for (int i = 0; i < 7500; ++i) {
        s.x.push_back(i / 500.0);
        s.y.push_back(1000.0 * c + 317.3 * std::sin(0.0063 * i + h) + 3.1 * std::sin(0.16 * i + c));
      }
      p.series.push_back(std::move(s));
    }
    r.plot(p);
  }
  const std::string h = r.html();
  EXPECT_LT(h.size(), 6'000'000u);
  const auto data = plot_data(h);
  for (const auto& p : data)
    for (const auto& s : p["series"]) EXPECT_LE(s["x"].size(), report::kReportMaxPoints);
  EXPECT_NE(h.find("drawn by 4000"), std::string::npos);
}

TEST(HtmlReport, WritesWholeFileOrNothing) {
  test::TempDir dir("rigflex-html");
  HtmlReport r("file");
  r.plot(line_plot("p", {1, 2}, {3, 4}));
  // Missing folders are made.
  const fs::path nested = dir.path() / "a" / "b" / "report.html";
  r.write(nested);
  EXPECT_EQ(test::read_text(nested), r.html());
  // A folder that cannot be made (a file is in the way): an exception naming
  // the report, and no file, whole or partial, left behind.
  const fs::path blocker = dir.path() / "blocker";
  test::write_text(blocker, "x");
  const fs::path target = blocker / "sub" / "report.html";
  try {
    r.write(target);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().string().find(".tmp-rigflex"), std::string::npos) << entry.path();
  // A failed write over an existing report keeps the old one.
  const fs::path existing = dir.path() / "existing.html";
  test::write_text(existing, "old");
  fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
  if (::geteuid() != 0) {  // root writes anyway
    EXPECT_THROW(r.write(existing), std::runtime_error);
    EXPECT_EQ(test::read_text(existing), "old");
  }
  fs::permissions(dir.path(), fs::perms::owner_all);
}

}  // namespace
}  // namespace rigflex
