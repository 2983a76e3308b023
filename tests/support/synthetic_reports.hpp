#pragma once
// Small synthetic results of a 3-rod rig for the command reports
// (report/reports.hpp): model comparisons with histories and residual analysis,
// diagnoses, identification reports and sweep points. Shared by the report
// tests (tests/io/test_reports.cpp, whose assertions rely on these values)
// and the browser check (tests/browser/make_compare_report.cpp, which asks
// for long histories and fine spectra).
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "report/reports.hpp"
#include "identify/identification_rig.hpp"
#include "diagnose/model_response.hpp"

namespace rigflex::test {

inline constexpr int kRods = 3;

// A history of a 3-rod rig: decaying swing on static rod loads; the model
// decays a little slower and misses a 12 Hz ringing.
inline diagnose::HistoryComparison history(int k, int samples = 400, double dt = 0.02) {
  diagnose::HistoryComparison h;
  h.source = "data/set1/h" + std::to_string(k + 1) + ".csv";
  h.target.record.step_s = dt;
  h.target.record.t = Eigen::VectorXd::LinSpaced(samples, 0.0, dt * (samples - 1));
  h.target.record.channels.resize(samples, 3 * kRods);
  h.model.resize(samples, 3 * kRods);
  for (int i = 0; i < samples; ++i) {
    const double t = i * dt;
    for (int c = 0; c < 3 * kRods; ++c) {
      const bool force = c < kRods;
      const double amp = force ? 400.0 : 0.05, base = force ? 9500.0 + 100 * c : 0.0;
      const double phase = 2 * std::numbers::pi * 0.55 * t + c + k;
      h.model(i, c) = base + amp * std::exp(-0.03 * t) * std::cos(phase);
      h.target.record.channels(i, c) =
          base + amp * std::exp(-0.05 * t) * std::cos(phase) + 0.02 * amp * std::sin(2 * std::numbers::pi * 12.3 * t);
    }
  }
  h.target.sigma = Eigen::VectorXd::Constant(3 * kRods, 1e-4);
  h.target.sigma.head(kRods).setConstant(2.0);
  // The swing band: here every sample, unfiltered.
  h.target.measured = h.target.record.channels;
  h.band_model = h.model;
  for (int i = 0; i < samples; ++i) h.target.at.push_back(i);
  h.nrmse = diagnose::nrmse_of(h.target.measured, h.band_model);
  h.raw_nrmse = diagnose::nrmse_of(h.measured(), h.model);
  h.fit_window_nrmse = 0.08;
  h.fit.converged = true;
  h.fit.iterations = 6;
  h.fit.whitened_rms = 1.4;
  return h;
}

inline diagnose::ResidualAnalysis analysis(const std::vector<std::string>& channels, int bins = 129) {
  const auto C = static_cast<Eigen::Index>(channels.size());
  diagnose::ResidualAnalysis a;
  a.channels = channels;
  a.noise = Eigen::VectorXd::Constant(C, 1e-4);
  a.noise_ratio = Eigen::VectorXd::LinSpaced(C, 1.5, 9.0);
  a.static_offset = Eigen::VectorXd::Zero(C);
  a.offset_in_noise = Eigen::VectorXd::Constant(C, 0.7);
  a.lag1 = Eigen::VectorXd::Constant(C, 0.95);
  a.channel_share = Eigen::VectorXd::Constant(C, 1.0 / static_cast<double>(C));
  for (int w = 0; w < 8; ++w) {
    a.trend_t.push_back(w + 0.5);
    a.trend_nrmse.push_back(0.05 + 0.01 * w);
  }
  a.trend_slope = 0.01;
  a.windows = {{1, 6.0, 7.0, 0.21}, {0, 7.0, 7.98, 0.18}};
  a.decay = {{0, 0.05, 0.03}, {1, 0.052, 0.03}};
  a.extra_decay_rate = 0.021;
  a.spectra.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 0.0, 25.0);
  a.spectra.residual_force.resize(bins);
  for (int k = 0; k < bins; ++k) {
    const double f = a.spectra.frequency_hz(k);
    a.spectra.residual_force(k) = 0.5 + 40 / (1 + 400 * (f - 0.55) * (f - 0.55)) + 8 / (1 + 40 * (f - 12.3) * (f - 12.3));
  }
  a.spectra.residual_angle = 1e-5 * a.spectra.residual_force;
  a.spectra.measured_force = 20 * a.spectra.residual_force;
  a.spectra.measured_angle = 20 * a.spectra.residual_angle;
  a.spectra.peaks = {{"force", 0.55, 40.5, 0.54}, {"force", 12.3, 8.5, 0.0}};
  a.mode_frequencies_hz = {0.54, 0.56, 0.81, 150.0};
  a.mode_kinds = {"swing", "swing", "swing", "rod constraint"};
  for (const char* s : {"angle", "velocity", "sign_of_velocity", "acceleration", "rod_force"})
    a.correlations.push_back({s, 0.31, "alpha2", Eigen::VectorXd::Constant(C, 0.1)});
  return a;
}

inline fe::MassProperties body(double zG = 0.812) {
  fe::MassProperties p;
  p.mass = 2914.0;
  p.cog = Eigen::Vector3d(0.01, -0.02, zG);
  p.inertia << 1500, -12, 30, -12, 4200, 5, 30, 5, 4800;
  return p;
}

inline diagnose::ModelComparison comparison(int samples = 400, double dt = 0.02) {
  diagnose::ModelComparison c;
  c.channels = diagnose::channel_names(kRods);
  c.histories = {history(0, samples, dt), history(1, samples, dt)};
  c.nrmse = diagnose::pooled_nrmse(c.histories);
  c.overall_nrmse = diagnose::rms_of(c.nrmse, 0, 3 * kRods);
  c.force_nrmse = diagnose::rms_of(c.nrmse, 0, kRods);
  c.angle_nrmse = diagnose::rms_of(c.nrmse, kRods, 2 * kRods);
  c.raw_nrmse = diagnose::pooled_nrmse(c.histories, true);
  c.raw_overall_nrmse = diagnose::rms_of(c.raw_nrmse, 0, 3 * kRods);
  c.raw_force_nrmse = diagnose::rms_of(c.raw_nrmse, 0, kRods);
  c.analysis = analysis(c.channels);
  c.algorithm = identify::IdentificationAlgorithm::flexible;
  identify::IdentificationResult id;
  id.observable = true;
  id.properties = body(0.8155);
  id.standard_deviation.fill(1e-3);
  id.equations = 750;
  id.condition_number = 42;
  c.identified = id;
  c.warnings = {"h2.csv: the model does not follow the data from the start"};
  return c;
}

inline report::CompareContext context() {
  report::CompareContext x;
  x.rig = "light-truck";
  x.model_label = "rig.yaml + drag.yaml";
  x.model_effects = {"air_drag"};
  x.reference = body();
  return x;
}

inline std::vector<report::StudyEntry> study() {
  report::StudyEntry a, b;
  a.version = 1;
  a.label = "rig.yaml";
  a.overall_nrmse = 0.3;
  a.force_nrmse = 0.25;
  b.version = 2;
  b.label = "rig.yaml + drag.yaml";
  b.overall_nrmse = 0.1;
  b.force_nrmse = 0.08;
  b.identified_cog_z = 0.8155;
  return {a, b};
}

inline diagnose::EffectFit effect(const std::string& name, double explained, bool significant) {
  diagnose::EffectFit e;
  e.effect = name;
  e.explained_fraction = explained;
  e.linear_explained_fraction = explained * 0.9;
  e.significant = significant;
  e.p_value = significant ? 1e-12 : 0.2;
  e.parameters = {{"coefficient", "N s/m", 12.5, 0.4, 0.0, 100.0, true}};
  e.advice = "add " + name + " to the rig file";
  e.rig_block = name + ": {coefficient: 12.5}\n";
  return e;
}

inline diagnose::Diagnosis diagnosis(bool with_missing, int samples = 400, double dt = 0.02) {
  diagnose::Diagnosis d;
  d.baseline = {history(0, samples, dt), history(1, samples, dt)};
  d.noise_ratio = 4.2;
  d.samples = 3600;
  d.independence = 0.4;
  d.present = {"rod_mass"};
  d.ranking = {effect("air_drag", 0.62, with_missing), effect("joint_friction", 0.2, false),
               effect("rod_compliance", 0.01, false)};
  if (with_missing) {
    d.missing_effect = "air_drag";
    d.summary = "missing effect: air_drag";
  } else {
    d.summary = "no significant missing effect: no effect of the catalogue explains the residual";
  }
  return d;
}

inline identify::IdentificationResult identified(double zG) {
  identify::IdentificationResult r;
  r.observable = true;
  r.properties = body(zG);
  r.positive_definite = r.triangle_inequality = true;
  r.condition_number = 55;
  r.equations = 700;
  return r;
}

inline report::IdentificationReport identification(bool reference) {
  report::IdentificationReport rep;
  rep.rig = "light-truck";
  rep.set_names = {"sets/s1", "sets/s2", "sets/s3", "sets/s4", "sets/s5"};
  rep.set_files.resize(5);
  if (reference) rep.reference = body();
  std::vector<identify::IdentificationResult> rigid, flexible;
  for (int k = 0; k < 5; ++k) {
    rigid.push_back(identified(0.861 + 0.002 * std::sin(k)));
    flexible.push_back(identified(0.812 + 0.0015 * std::cos(k)));
  }
  rep.add(identify::IdentificationAlgorithm::rigid, rigid);
  rep.add(identify::IdentificationAlgorithm::flexible, flexible);
  return rep;
}

inline identify::ErrorSummary errors(double zG_m, double jyy) {
  identify::ErrorSummary e;
  e.sets = 3;
  e.zG_mean_m = zG_m;
  e.zG_std_m = 0.1 * std::abs(zG_m);
  e.moment_mean = {0.0, jyy, 0.0};
  return e;
}

inline std::vector<identify::SweepPoint> sweep_points() {
  std::vector<identify::SweepPoint> pts;
  for (int k = 0; k < 4; ++k) {
    for (const auto kind : {identify::SweepKind::mass, identify::SweepKind::stiffness}) {
      identify::SweepPoint p;
      p.kind = kind;
      p.scale = std::pow(2.0, k);
      p.f1_hz = kind == identify::SweepKind::mass ? 8.0 / std::sqrt(p.scale) : 2.0 * std::sqrt(p.scale);
      p.swing_max_hz = 0.6;
      p.ratio = *p.f1_hz / 0.6;
      p.rigid = errors(0.05 / *p.ratio, 0.1 / *p.ratio);
      p.flexible = errors(0.001, 0.002);
      pts.push_back(p);
    }
  }
  pts[1].rigid.reset();
  pts[1].failure = "rigid: not observable";
  identify::SweepPoint rigid_rods;
  rigid_rods.kind = identify::SweepKind::stiffness;
  rigid_rods.scale = 100;
  rigid_rods.failure = "no static equilibrium";
  pts.push_back(rigid_rods);
  return pts;
}

}  // namespace rigflex::test
