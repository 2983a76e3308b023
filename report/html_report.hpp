#pragma once
// A self-contained HTML report: one file that opens offline in any browser,
// with headings, paragraphs, tables and interactive plots. The plotting
// library (Chart.js 4, MIT, from the npm registry; docs/reports.md) and the
// plot data are inlined; the document refers to no other file or URL.
//
// The page checks itself: errors (window.onerror, console.error, unhandled
// rejections) are collected in window.__reportErrors; once every chart is
// drawn, <body> carries data-plots (plots in the document), data-plots-rendered
// (charts created whose canvas holds ink, and coloured ink when the plot has
// data) and data-errors (error count). tests/browser/check_report.sh reads them
// in headless Chromium.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rigflex::report {

// Series longer than this are decimated for display (Plot::max_points).
inline constexpr std::size_t kReportMaxPoints = 4000;
// Per series of a small multiple (a third of the page wide): 1500 points are
// still several per pixel column.
inline constexpr std::size_t kSmallPlotPoints = 1500;

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;   // same length; bar charts use y only (one per category)
  bool points = false;        // markers without a line (line plots)
  std::vector<double> dash;   // line dash pattern in px, e.g. {6, 3}; empty: solid
};

// A labelled vertical line across the plot at x (e.g. a mode frequency).
struct PlotMarker {
  double x = 0.0;
  std::string label;
};

struct Plot {
  enum class Kind { line, scatter, bar };
  Kind kind = Kind::line;
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;   // log_x is not allowed for bar charts
  std::vector<std::string> categories; // bar charts: the x labels
  std::vector<PlotSeries> series;
  std::vector<PlotMarker> markers;     // line and scatter plots
  std::size_t max_points = kReportMaxPoints;  // per series, at least 8
};

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as wide as the header (when there is one)
};

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  // Blocks appear in the order they are added. Text is escaped (plain text,
  // line breaks kept), never interpreted as HTML.
  void heading(const std::string& text);
  void paragraph(const std::string& text);
  void table(const Table& t, const std::string& caption = "");
  // Throws std::invalid_argument naming the plot and series when the data do
  // not fit the plot (x and y of different length, bar values not one per
  // category, log_x on a bar chart, max_points below 8). Non-finite values,
  // and values <= 0 on a log axis, are gaps (a point without x is dropped).
  // Numbers are kept to 7 significant digits, far below a screen pixel.
  void plot(const Plot& p);
  // Plots of one kind side by side, `columns` to a row, smaller, under one
  // caption (a channel each: one crowded chart becomes a grid a reader
  // scans). Each plot is checked as plot() checks it and counts as a plot.
  // Throws std::invalid_argument for columns < 1.
  void small_multiples(const std::vector<Plot>& plots, int columns, const std::string& caption);

  std::string html() const;  // the whole document
  // Writes html() through io::write_atomically: the file appears whole or not
  // at all; throws std::runtime_error naming `file` when it cannot be written.
  void write(const std::filesystem::path& file) const;
  int plot_count() const;

 private:
  struct Figure {
    std::string canvas;  // the plot's box and canvas
    std::size_t decimated = 0, longest = 0;
  };
  // Records the plot's data; `what` names an untitled plot for screen readers.
  Figure figure(const Plot& p, const char* what);

  std::string title_;
  std::string body_;                    // HTML of the blocks so far
  std::vector<std::string> plot_data_;  // one JSON object per plot
};

// Min/max decimation for display: a series of n > max_points points becomes
// its first and last points plus, over equal index buckets between them, each
// bucket's lowest and highest y (in index order), and the first gap (non-finite
// y) of a bucket when there is one; at most max_points points, global extremes
// and gaps kept. Shorter series are returned unchanged. Points whose x is not
// finite are dropped first. Throws std::invalid_argument when max_points < 8.
// (A report of 6 histories x 12 channels x 7500 samples is 4.5 MB: see
// docs/reports.md.)
PlotSeries decimate_min_max(const PlotSeries& s, std::size_t max_points);

// Text for HTML content and attribute values: & < > " ' escaped.
std::string escape_html(std::string_view text);

// The inlined Chart.js bundle (chart.umd.js, with its MIT licence comment).
std::string_view chart_js();

}  // namespace rigflex::report
