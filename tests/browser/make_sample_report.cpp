// Writes a sample HTML report for the browser test (tests/browser/check_report.sh).
//   make_sample_report OUT.html           4 plots: line with markers, log-log, scatter, bar; a table
//   make_sample_report OUT.html --large   6 plots of 12 channels x 7500 samples (6 swings of 15 s at 500 Hz)
// Prints the number of plots written.
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

#include "report/html_report.hpp"

namespace {

using rigflex::report::HtmlReport;
using rigflex::report::Plot;
using rigflex::report::PlotSeries;

constexpr double pi = std::numbers::pi;

void sample(HtmlReport& r) {
  r.heading("Free swing");
  r.paragraph("Load cell forces of the first history.\nEscaping check: <b>not bold</b> & \"quoted\" </script>");
  Plot swing;
  swing.title = "Rod forces </script><!-- (h1)";
  swing.x_label = "t (s)";
  swing.y_label = "F (N)";
  for (int rod = 0; rod < 3; ++rod) {
    PlotSeries s;
    s.label = "F" + std::to_string(rod + 1);
    for (int i = 0; i < 7500; ++i) {
      const double t = i / 500.0;
      s.x.push_back(t);
      s.y.push_back(9500 + 100 * rod + 400 * std::exp(-0.05 * t) * std::cos(2 * pi * 0.55 * t + rod) +
                    15 * std::sin(2 * pi * 11.3 * t));
    }
    if (rod == 2) s.dash = {6, 3};
    if (rod == 1) s.y[3000] = std::nan("");  // a gap
    swing.series.push_back(std::move(s));
  }
  swing.markers = {{5.0, "release"}, {10.0, "t = 10 s"}};
  r.plot(swing);

  r.heading("Spectrum");
  Plot spectrum;
  spectrum.title = "Amplitude spectrum";
  spectrum.x_label = "f (Hz)";
  spectrum.y_label = "|F| (N)";
  spectrum.log_x = spectrum.log_y = true;
  PlotSeries a{"F1", {}, {}, false, {}};
  for (int i = 0; i <= 2000; ++i) {
    const double f = 0.05 * std::pow(10.0, i / 500.0);  // 0.05 .. 500 Hz
    a.x.push_back(f);
    a.y.push_back(1.0 / std::hypot(1 - std::pow(f / 0.55, 2), 0.04 * f / 0.55) +
                  0.2 / std::hypot(1 - std::pow(f / 11.3, 2), 0.04 * f / 11.3));
  }
  spectrum.series.push_back(std::move(a));
  spectrum.markers = {{0.55, "swing 0.55 Hz"}, {11.3, "mode 1 11.3 Hz"}};
  r.plot(spectrum);

  r.heading("Identification");
  Plot scatter;
  scatter.kind = Plot::Kind::scatter;
  scatter.title = "CoG height per history";
  scatter.x_label = "history";
  scatter.y_label = "zG (mm)";
  PlotSeries rigid{"rigid", {}, {}, true, {}}, flexible{"flexible", {}, {}, true, {}};
  for (int h = 1; h <= 6; ++h) {
    rigid.x.push_back(h);
    rigid.y.push_back(812 + 49 + 3 * std::sin(h));
    flexible.x.push_back(h);
    flexible.y.push_back(812 + 2 * std::cos(h));
  }
  scatter.series = {rigid, flexible};
  r.plot(scatter);

  Plot bars;
  bars.kind = Plot::Kind::bar;
  bars.title = "Strain energy shares";
  bars.y_label = "share (%)";
  bars.categories = {"fixed frame", "rods", "carrying frame", "joints"};
  bars.series = {{"mode 1", {}, {62, 21, 14, 3}, false, {}}, {"mode 2", {}, {30, 45, 20, 5}, false, {}}};
  r.plot(bars);

  r.table({{"quantity", "rigid", "flexible", "reference"},
           {{"m (kg)", "2914.2", "2914.0", "2914"}, {"zG (mm)", "861", "812", "812"}, {"<Jyy> & co", "1", "2", "3"}}},
          "Mass properties");
}

void large(HtmlReport& r) {
  for (int h = 0; h < 6; ++h) {
    r.heading("History " + std::to_string(h + 1));
    Plot p;
    p.title = "h" + std::to_string(h + 1) + ": load cells and encoders";
    p.x_label = "t (s)";
    p.y_label = "signal";
    for (int c = 0; c < 12; ++c) {
      PlotSeries s;
      s.label = "channel " + std::to_string(c + 1);
      s.x.reserve(7500);
      s.y.reserve(7500);
      for (int i = 0; i < 7500; ++i) {
        const double t = i / 500.0;
        s.x.push_back(t);
        s.y.push_back(1000.0 * (c + 1) + 317.3 * std::exp(-0.03 * t) * std::sin(2 * pi * (0.5 + 0.01 * c) * t + h) +
                      3.1 * std::sin(2 * pi * 12.7 * t + c));
      }
      p.series.push_back(std::move(s));
    }
    p.markers = {{7.5, "mid-record"}};
    r.plot(p);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3 || (argc == 3 && std::string(argv[2]) != "--large")) {
    std::fprintf(stderr, "usage: make_sample_report OUT.html [--large]\n");
    return 2;
  }
  try {
    const bool big = argc == 3;
    HtmlReport r(big ? "rigflex sample report: 6 histories x 12 channels" : "rigflex sample report <&>");
    if (big)
      large(r);
    else
      sample(r);
    r.write(argv[1]);
    std::printf("%d\n", r.plot_count());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_sample_report: %s\n", e.what());
    return 1;
  }
  return 0;
}
