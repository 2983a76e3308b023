// Writes a command report (report/reports.hpp) from the synthetic results of
// tests/support/synthetic_reports.hpp, for the browser test
// (tests/browser/check_report.sh):
//   make_compare_report compare OUT.html          23 plots: 2 histories x 9 channels x 7500 samples
//   make_compare_report diagnosis OUT.html        14 plots: 3 ranked effects, baseline with its analysis
//   make_compare_report identification OUT.html   2 plots: rigid and flexible, 5 sets, reference
//   make_compare_report sweep OUT.html            2 plots: mass and stiffness sweeps
// Prints the number of plots written.
#include <cstdio>
#include <exception>
#include <string>

#include "report/reports.hpp"
#include "support/synthetic_reports.hpp"

namespace {

using namespace rigflex;

constexpr int kSamples = 7500;  // 15 s at 500 Hz
constexpr double kStep = 0.002;
constexpr int kBins = 2049;  // spectrum bins

report::HtmlReport compare() {
  diagnose::ModelComparison c = test::comparison(kSamples, kStep);
  c.analysis = test::analysis(c.channels, kBins);
  c.histories[1].source = "data/set1/h2 <odd> & \"quoted\".csv";  // escaped in the page
  return report::compare_report(c, test::context(), test::study());
}

report::HtmlReport diagnosis() {
  const diagnose::Diagnosis d = test::diagnosis(true, kSamples, kStep);
  const diagnose::ResidualAnalysis a = test::analysis(diagnose::channel_names(test::kRods), kBins);
  return report::diagnosis_report(d, test::context(), &a);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string kind = argc == 3 ? argv[1] : "";
  if (kind != "compare" && kind != "diagnosis" && kind != "identification" && kind != "sweep") {
    std::fprintf(stderr, "usage: make_compare_report compare|diagnosis|identification|sweep OUT.html\n");
    return 2;
  }
  try {
    const report::HtmlReport r = kind == "compare"     ? compare()
                             : kind == "diagnosis" ? diagnosis()
                             : kind == "sweep"     ? report::sweep_html("light-truck", test::sweep_points())
                                                   : report::identification_html(test::identification(true));
    r.write(argv[2]);
    std::printf("%d\n", r.plot_count());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_compare_report: %s\n", e.what());
    return 1;
  }
  return 0;
}
