// The command reports (report/reports.hpp) from small synthetic results: the
// plots each report promises, the key text, robustness to missing parts and
// non-finite values, and errors only for data that contradict themselves.
// (Rendering in a browser: tests/browser/make_compare_report.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "identify/mass_statistics.hpp"
#include "report/compare_json.hpp"
#include "report/identification_report.hpp"
#include "report/reports.hpp"
#include "support/synthetic_reports.hpp"

namespace rigflex {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using namespace test;  // the synthetic inputs

// ---------------------------------------------------------------- reading the reports

bool has(const report::HtmlReport& r, const std::string& text) { return r.html().find(text) != std::string::npos; }

nlohmann::json plot_data(const report::HtmlReport& r) {
  const std::string html = r.html();
  const std::string open = "<script type=\"application/json\" id=\"report-data\">";
  const auto begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const auto end = html.find("</script>", begin);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

// ---------------------------------------------------------------- compare

TEST(CompareReport, HasEveryPlotAndSection) {
  const report::HtmlReport r = report::compare_report(comparison(), context(), study());
  // a small plot per channel (3 x kRods) of measured and model, again of the residual, 2 spectra, trend, decay,
  // study
  constexpr int kChannels = 3 * kRods;
  EXPECT_EQ(r.plot_count(), 2 * kChannels + 5);
  for (const char* s :
       {"Measured (solid) and model (dashed) per channel", "Residual (measured − model) per channel",
        "a rod per column", "grid-template-columns: repeat(3,", "Residual spectrum, forces", "swing 0.54, 0.56 Hz",
        "swing 0.81 Hz", "rod constraint 150 Hz", "Overall NRMSE per window", "Decay rate per history", "v1 rig.yaml",
        "v2 rig.yaml + drag.yaml", "sign_of_velocity", "light-truck", "Warning: h2.csv: the model does not follow",
        "identified − reference", "zG (mm)", "3.50"})
    EXPECT_TRUE(has(r, s)) << s;
  const nlohmann::json data = plot_data(r);
  ASSERT_EQ(data.size(), 2u * kChannels + 5);
  const std::vector<std::string> names = diagnose::channel_names(kRods);
  for (int c = 0; c < kChannels; ++c) {  // the channel's own plot, its unit on the axis, both curves
    const auto& plot = data[c];
    const auto& residual = data[kChannels + c];
    EXPECT_EQ(plot["title"], names[c]);
    EXPECT_EQ(plot["y_label"], names[c] + (c < kRods ? " (N)" : " (rad)"));
    ASSERT_EQ(plot["series"].size(), 2u);
    EXPECT_EQ(plot["series"][0]["label"], "measured");
    EXPECT_EQ(plot["series"][1]["label"], "model");
    EXPECT_EQ(residual["title"], names[c]);
    EXPECT_EQ(residual["y_label"], std::string(c < kRods ? "residual (N)" : "residual (rad)"));
    ASSERT_EQ(residual["series"].size(), 1u);
    EXPECT_LE(plot["series"][0]["x"].size(), report::kSmallPlotPoints);
  }
  EXPECT_EQ(data[2 * kChannels]["markers"].size(), 4u);  // the model's modes
  EXPECT_EQ(data[2 * kChannels + 4]["categories"][0], "v1 rig.yaml");
}

TEST(CompareReport, EmptyStudyAndMissingIdentification) {
  diagnose::ModelComparison c = comparison();
  c.identified.reset();
  c.identification_error = "CoG height not observable";
  report::CompareContext x = context();
  x.reference.reset();
  const report::HtmlReport r = report::compare_report(c, x, {});
  EXPECT_EQ(r.plot_count(), 2 * 3 * kRods + 4);
  EXPECT_FALSE(has(r, "Error by model version"));
  EXPECT_TRUE(has(r, "Not identified (flexible algorithm): CoG height not observable"));
}

TEST(CompareReport, NonFiniteValuesAreGapsAndDashes) {
  diagnose::ModelComparison c = comparison();
  c.overall_nrmse = kNaN;
  c.nrmse(2) = kNaN;
  c.histories[0].target.record.channels(10, 0) = kNaN;
  c.histories[0].model(11, 4) = std::numeric_limits<double>::infinity();
  c.analysis.spectra.residual_force(3) = kNaN;
  c.analysis.decay[1].measured_rate = kNaN;
  c.analysis.trend_nrmse[2] = kNaN;
  c.analysis.mode_frequencies_hz[0] = kNaN;
  c.identified->properties.cog.z() = kNaN;
  std::vector<report::StudyEntry> s = study();
  s[0].overall_nrmse = kNaN;
  report::HtmlReport r("");
  ASSERT_NO_THROW(r = report::compare_report(c, context(), s));
  EXPECT_EQ(r.plot_count(), 2 * 3 * kRods + 5);
  EXPECT_TRUE(has(r, "<td>–</td>"));
}

TEST(CompareReport, EmptyComparisonGivesAReportWithoutPlots) {
  report::HtmlReport r("");
  ASSERT_NO_THROW(r = report::compare_report(diagnose::ModelComparison{}, report::CompareContext{}, {}));
  EXPECT_EQ(r.plot_count(), 0);
  EXPECT_TRUE(has(r, "Not identified."));
}

TEST(CompareReport, ContradictoryDataThrowNamingIt) {
  diagnose::ModelComparison c = comparison();
  c.histories[1].model.conservativeResize(Eigen::NoChange, 3 * kRods - 1);
  EXPECT_THROW(
      {
        try {
          report::compare_report(c, context(), {});
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("history 2"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
  c = comparison();
  c.analysis.spectra.measured_angle.resize(5);
  EXPECT_THROW(report::compare_report(c, context(), {}), std::invalid_argument);
  c = comparison();
  c.channels.pop_back();
  EXPECT_THROW(report::compare_report(c, context(), {}), std::invalid_argument);
}

TEST(CompareReport, EscapesSources) {
  diagnose::ModelComparison c = comparison();
  c.histories[0].source = "<script>alert(1)</script>.csv";
  const std::string h = report::compare_report(c, context(), {}).html();
  EXPECT_EQ(h.find("<script>alert(1)"), std::string::npos);
  EXPECT_NE(h.find("&lt;script&gt;alert(1)"), std::string::npos);
}

// ---------------------------------------------------------------- diagnosis

TEST(DiagnosisReport, RanksEffectsAndAdvisesOnTheMissingOne) {
  const diagnose::Diagnosis d = diagnosis(true);
  const report::HtmlReport r = report::diagnosis_report(d, context());
  EXPECT_EQ(r.plot_count(), 1 + 3 * kRods);  // ranking, the baseline's residual per channel
  for (const char* s : {"missing effect: air_drag", "air_drag *", "joint_friction", "rod_compliance",
                        "12.5 ± 0.4", "N s/m", "add air_drag to the rig file", "air_drag: {coefficient: 12.5}",
                        "Missing effect: air_drag", "4.2 × the noise"})
    EXPECT_TRUE(has(r, s)) << s;
  EXPECT_FALSE(has(r, "joint_friction *"));
  const nlohmann::json data = plot_data(r);
  ASSERT_EQ(data[0]["categories"].size(), 3u);
  EXPECT_EQ(data[0]["categories"][0], "air_drag *");
  EXPECT_DOUBLE_EQ(data[0]["series"][0]["y"][1].get<double>(), 20.0);
}

TEST(DiagnosisReport, KeepsTheIndentationOfTheRigBlock) {
  diagnose::Diagnosis d = diagnosis(true);
  d.ranking[0].rig_block = "fixed_frame_flexibility:\n  joint_compliance:\n    twist: 1e-07\n";
  const report::HtmlReport r = report::diagnosis_report(d, context());
  EXPECT_TRUE(has(r, "fixed_frame_flexibility:\n\u00a0\u00a0joint_compliance:\n\u00a0\u00a0\u00a0\u00a0twist: 1e-07"));
  EXPECT_TRUE(has(r, "effects/air_drag.yaml"));
}

// Two effects found one after the other: the chain's table with the
// residual after each step, what was tested at the second step, and the
// block that adds both; the JSON carries the same.
TEST(DiagnosisReport, ShowsTheChainWithTheErrorAfterEachStep) {
  diagnose::Diagnosis d = diagnosis(true);
  diagnose::ChainStep first;
  first.effect = "air_drag";
  first.noise_ratio = 2.5;
  first.rig_block = d.ranking[0].rig_block;
  diagnose::ChainStep second;
  second.effect = "joint_friction";
  second.noise_ratio = 1.05;
  second.p_value = 1e-12;
  second.rig_block = d.ranking[0].rig_block + "joint_friction: {viscous: 0.3}\n";
  second.ranking = {effect("joint_friction", 0.55, true), effect("rod_compliance", 0.01, false)};
  d.chain = {first, second};
  const report::HtmlReport r = report::diagnosis_report(d, context());
  for (const char* s : {"The chain: effects added one after another", "(the model as it is)", "2.5", "1.05",
                        "joint_friction *, rod_compliance", "effects/found.yaml", "joint_friction: {viscous: 0.3}"})
    EXPECT_TRUE(has(r, s)) << s;
  const nlohmann::json j = report::diagnosis_json(d, context());
  ASSERT_EQ(j["chain"].size(), 2u);
  EXPECT_EQ(j["chain"][1]["effect"], "joint_friction");
  EXPECT_DOUBLE_EQ(j["chain"][1]["residual_to_noise"].get<double>(), 1.05);
  EXPECT_EQ(j["chain"][1]["tested"].size(), 2u);
  EXPECT_EQ(j["chain"][1]["rig_block"], second.rig_block);
  EXPECT_TRUE(j["tested_after_chain"].empty());
  // One effect and nothing further significant on top of it: the table
  // still shows the step, and what was tested after it.
  d.chain = {first};
  d.after_chain = {effect("rod_compliance", 0.01, false)};
  const report::HtmlReport one = report::diagnosis_report(d, context());
  EXPECT_TRUE(has(one, "Tested on top of the whole chain, none significant: rod_compliance."));
  d.after_chain.clear();
  EXPECT_FALSE(has(report::diagnosis_report(d, context()), "The chain:"));
  d.chain_note = "the chain stops at air_drag";
  EXPECT_TRUE(has(report::diagnosis_report(d, context()), "Note: the chain stops at air_drag."));
  EXPECT_EQ(report::diagnosis_json(d, context())["chain_note"], "the chain stops at air_drag");
}

TEST(DiagnosisReport, WithTheBaselineAnalysisAddsSpectraTrendAndDecay) {
  const diagnose::Diagnosis d = diagnosis(true);
  const diagnose::ResidualAnalysis a = analysis(diagnose::channel_names(kRods));
  const report::HtmlReport r = report::diagnosis_report(d, context(), &a);
  EXPECT_EQ(r.plot_count(), 1 + 3 * kRods + 4);
  EXPECT_TRUE(has(r, "Residual spectrum, angles"));
}

TEST(DiagnosisReport, NoSignificantEffect) {
  diagnose::Diagnosis d = diagnosis(false);
  report::HtmlReport r = report::diagnosis_report(d, context());
  EXPECT_TRUE(has(r, "no significant missing effect"));
  EXPECT_FALSE(has(r, "air_drag *"));
  EXPECT_FALSE(has(r, "Missing effect:"));
  d.summary.clear();
  d.ranking.clear();
  d.baseline.clear();
  ASSERT_NO_THROW(r = report::diagnosis_report(d, report::CompareContext{}));
  EXPECT_EQ(r.plot_count(), 0);
  EXPECT_TRUE(has(r, "no significant missing effect"));
}

TEST(DiagnosisReport, NonFiniteValuesDoNotThrow) {
  diagnose::Diagnosis d = diagnosis(true);
  d.ranking[1].explained_fraction = kNaN;
  d.ranking[0].parameters[0].std = kNaN;
  d.noise_ratio = kNaN;
  d.baseline[0].target.record.channels(0, 0) = kNaN;
  report::HtmlReport r("");
  ASSERT_NO_THROW(r = report::diagnosis_report(d, context()));
  EXPECT_EQ(r.plot_count(), 1 + 3 * kRods);
}

// ---------------------------------------------------------------- identification

TEST(IdentificationHtml, TablesAndNormalProbabilityAgainstTheReference) {
  const report::IdentificationReport rep = identification(true);
  const report::HtmlReport r = report::identification_html(rep);
  EXPECT_EQ(r.plot_count(), 2);  // one per algorithm
  for (const char* s : {"rigid mean ± std", "flexible − reference", "zG − reference zG (mm)", "Welch t",
                        "inside the rig", "s3", "normal line", "flexible algorithm: CoG height",
                        "<td>861.45 ± 1.37</td>", "<td>4200.0</td>"})
    EXPECT_TRUE(has(r, s)) << s;
  {  // no floating-point dust (4200 ± 1e-13) in the mass properties table
    const std::string h = r.html();
    const auto from = h.find("<h2>Mass properties"), to = h.find("<h2>CoG height");
    ASSERT_LT(from, to);
    EXPECT_EQ(h.substr(from, to - from).find("e-"), std::string::npos);
  }
  // The plotted differences are identification.json's normal_probability (in mm).
  const nlohmann::json data = plot_data(r);
  const auto json = rep.json();
  const auto& pts = json["normal_probability"]["points"];  // the primary (last: flexible) algorithm
  const auto& series = data[1]["series"];
  ASSERT_EQ(series.size(), 4u);  // sets, normal line, the 2-sigma band's two edges
  ASSERT_EQ(series[0]["x"].size(), pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_NEAR(series[0]["x"][i].get<double>(), 1e3 * pts[i]["value"].get<double>(), 1e-4);
    EXPECT_NEAR(series[0]["y"][i].get<double>(), pts[i]["quantile"].get<double>(), 1e-6);
  }
  // The band: the line's mean and sd (from the line's two ends) times each rank's order-statistic
  // quantiles, at the points' heights; the second edge has no label (one legend entry).
  EXPECT_EQ(series[2]["label"], "2σ band");
  EXPECT_EQ(series[3]["label"], "");
  const auto& line = series[1];
  const double z0 = line["y"][0].get<double>(), z1 = line["y"][1].get<double>();
  const double sd = (line["x"][1].get<double>() - line["x"][0].get<double>()) / (z1 - z0);
  const double mean = line["x"][0].get<double>() - sd * z0;
  const auto band = identify::normal_order_statistic_band(pts.size(), 2.0);
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_NEAR(series[2]["x"][i].get<double>(), mean + sd * band[i].lower, 1e-3);
    EXPECT_NEAR(series[3]["x"][i].get<double>(), mean + sd * band[i].upper, 1e-3);
    EXPECT_EQ(series[2]["y"][i], series[0]["y"][i]);
    const double x = series[0]["x"][i].get<double>();  // these five sets are no outliers
    EXPECT_GT(x, series[2]["x"][i].get<double>());
    EXPECT_LT(x, series[3]["x"][i].get<double>());
  }
}

// Each history identified alone (a test) is the probability plot's sample when
// the tests outnumber the sets; the sets' result is a marker; a test that is
// not observable alone is listed with its message and left out.
TEST(IdentificationHtml, EveryTestIsAPointOfTheProbabilityPlot) {
  report::IdentificationReport rep;
  rep.set_names = {"set1"};
  rep.set_files = {{"h1.csv", "h2.csv", "h3.csv", "h4.csv"}};
  rep.reference = body();
  std::vector<report::IdentificationReport::Test> tests;
  for (int h = 0; h < 4; ++h) {
    report::IdentificationReport::Test t;
    t.set = 0;
    t.file = "h" + std::to_string(h + 1) + ".csv";
    t.result = identified(0.812 + 0.001 * (h - 1.5));
    tests.push_back(t);
  }
  tests[2].result.observable = false;
  tests[2].result.message = "Jxx not observable";
  rep.add(identify::IdentificationAlgorithm::flexible, {identified(0.8121)}, tests);
  const auto json = rep.json();
  ASSERT_EQ(json["tests"].size(), 4u);
  EXPECT_EQ(json["tests"][2]["observable"], false);
  EXPECT_EQ(json["tests"][2]["message"], "Jxx not observable");
  EXPECT_FALSE(json["tests"][2].contains("cog"));
  EXPECT_NEAR(json["tests"][3]["cog"][2].get<double>(), 0.8135, 1e-12);
  EXPECT_EQ(json["normal_probability"]["of"], "tests");
  ASSERT_EQ(json["normal_probability"]["points"].size(), 3u);  // the three observable tests
  const report::HtmlReport r = report::identification_html(rep);
  const nlohmann::json data = plot_data(r);
  ASSERT_EQ(data.size(), 1u);
  EXPECT_EQ(data[0]["series"][0]["label"], "tests (each history alone)");
  ASSERT_EQ(data[0]["series"][0]["x"].size(), 3u);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(data[0]["series"][0]["x"][i].get<double>(),
                1e3 * json["normal_probability"]["points"][i]["value"].get<double>(), 1e-4);
  ASSERT_EQ(data[0]["markers"].size(), 1u);  // the set's own result, against the reference
  EXPECT_NEAR(data[0]["markers"][0]["x"].get<double>(), 1e3 * (0.8121 - body().cog.z()), 1e-4);
  // Tests that do not outnumber the sets leave the sets as the sample.
  report::IdentificationReport two = identification(true);
  for (auto& a : two.algorithms) a.tests.clear();
  EXPECT_EQ(report::height_sample(two.algorithms[0]).of, "sets");
  EXPECT_EQ(report::height_sample(two.algorithms[0]).z.size(), 5u);
  // A test naming a set that does not exist is refused.
  report::IdentificationReport bad;
  bad.set_names = {"set1"};
  tests[0].set = 3;
  EXPECT_THROW(bad.add(identify::IdentificationAlgorithm::rigid, {identified(0.8)}, tests), std::invalid_argument);
}

TEST(IdentificationHtml, StaticHeightWithTareMatchesTheJson) {
  report::IdentificationReport rep;
  rep.set_names = {"a", "b", "c"};
  rep.set_files.resize(3);
  fe::MassProperties tare;
  tare.mass = 400;
  tare.cog = Eigen::Vector3d(0, 0, 0.3);
  rep.tare = tare;
  rep.static_cog_height = 0.75;
  rep.add(identify::IdentificationAlgorithm::rigid, {identified(0.74), identified(0.752), identified(0.749)});
  const nlohmann::json data = plot_data(report::identification_html(rep));
  const auto pts = rep.json()["normal_probability"]["points"];
  ASSERT_EQ(data[0]["series"][0]["x"].size(), 3u);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(data[0]["series"][0]["x"][i].get<double>(), 1e3 * pts[i]["value"].get<double>(), 1e-4);
  EXPECT_NE(data[0]["x_label"].get<std::string>().find("static zG"), std::string::npos);
}

TEST(IdentificationHtml, WithoutReferenceDifferencesFromTheMean) {
  report::IdentificationReport rep = identification(false);
  rep.algorithms[0].records[2].cog.z() = kNaN;  // one set without a height: left out
  report::HtmlReport r("");
  ASSERT_NO_THROW(r = report::identification_html(rep));
  EXPECT_EQ(r.plot_count(), 2);
  EXPECT_TRUE(has(r, "zG − mean zG (mm)"));
  EXPECT_TRUE(has(r, "Not tested (non-finite"));
  const nlohmann::json data = plot_data(r);
  EXPECT_EQ(data[0]["series"][0]["x"].size(), 4u);
  double sum = 0;
  for (const auto& x : data[1]["series"][0]["x"]) sum += x.get<double>();
  EXPECT_NEAR(sum, 0.0, 1e-3);  // flexible: about its own mean
}

TEST(IdentificationHtml, ImposedCogHasNothingToPlot) {
  report::IdentificationReport rep = identification(true);
  rep.options.cog_constraint = identify::CogConstraint::full;
  const report::HtmlReport r = report::identification_html(rep);
  EXPECT_EQ(r.plot_count(), 0);
  EXPECT_TRUE(has(r, "no scatter to plot"));
}

TEST(IdentificationHtml, MismatchedResultsThrow) {
  report::IdentificationReport rep = identification(true);
  rep.algorithms[1].records.pop_back();
  EXPECT_THROW(report::identification_html(rep), std::invalid_argument);
}

// ---------------------------------------------------------------- sweep

TEST(SweepHtml, ErrorCurvesAgainstF1) {
  const report::HtmlReport r = report::sweep_html("light-truck", sweep_points());
  EXPECT_EQ(r.plot_count(), 2);
  for (const char* s : {"rigid, mass sweep", "flexible, stiffness sweep", "no static equilibrium",
                        "rigid: not observable", "3 × highest swing 1.8 Hz"})
    EXPECT_TRUE(has(r, s)) << s;
  const nlohmann::json data = plot_data(r);
  EXPECT_TRUE(data[0]["log_x"].get<bool>());
  ASSERT_EQ(data[0]["series"].size(), 4u);
  const auto& x = data[0]["series"][0]["x"];  // rigid, mass sweep: by f1
  for (size_t i = 1; i < x.size(); ++i) EXPECT_LT(x[i - 1].get<double>(), x[i].get<double>());
}

TEST(SweepHtml, NoPointsOrNoF1) {
  report::HtmlReport r("");
  ASSERT_NO_THROW(r = report::sweep_html("", {}));
  EXPECT_EQ(r.plot_count(), 0);
  std::vector<identify::SweepPoint> pts(2);
  pts[0].failure = "nothing deforms";
  ASSERT_NO_THROW(r = report::sweep_html("x", pts));
  EXPECT_EQ(r.plot_count(), 0);
  EXPECT_TRUE(has(r, "no error curve"));
}

// ---------------------------------------------------------------- every command report

// A reviewer reads a chart at a glance only when it says what it shows: every
// plot of the four command reports has a title, both axes labelled with their
// unit in parentheses (a bar chart's categories name what they are instead),
// a legend entry per series (a band's second edge continues the one before
// it) and data to draw.
TEST(CommandReports, EveryChartHasUnitsLegendsAndData) {
  const diagnose::ResidualAnalysis a = analysis(diagnose::channel_names(kRods));
  diagnose::ModelComparison c = comparison();
  c.analysis = a;
  const std::vector<std::pair<std::string, report::HtmlReport>> reports = {
      {"compare", report::compare_report(c, context(), study())},
      {"diagnosis", report::diagnosis_report(diagnosis(true), context(), &a)},
      {"identification", report::identification_html(identification(true))},
      {"sweep", report::sweep_html("light-truck", sweep_points())}};
  for (const auto& [name, r] : reports) {
    const nlohmann::json data = plot_data(r);
    ASSERT_GT(data.size(), 0u) << name;
    for (size_t i = 0; i < data.size(); ++i) {
      const auto& p = data[i];
      const std::string where = name + " plot " + std::to_string(i + 1) + " (" + p["title"].get<std::string>() + ")";
      const bool bar = p["kind"] == "bar";
      const std::string x = p["x_label"], y = p["y_label"];
      EXPECT_FALSE(p["title"].get<std::string>().empty()) << where;
      EXPECT_FALSE(x.empty()) << where;
      EXPECT_TRUE(y.find('(') != std::string::npos && y.find(')') != std::string::npos) << where << ": " << y;
      if (!bar) {
        EXPECT_TRUE(x.find('(') != std::string::npos && x.find(')') != std::string::npos) << where << ": " << x;
      }
      ASSERT_GT(p["series"].size(), 0u) << where;
      EXPECT_FALSE(p["series"][0]["label"].get<std::string>().empty()) << where;
      bool finite = false;
      for (const auto& series : p["series"])
        for (const auto& v : series["y"]) finite = finite || v.is_number();
      EXPECT_TRUE(finite) << where << ": no data";
    }
  }
}

}  // namespace
}  // namespace rigflex
