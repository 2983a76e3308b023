#include "report/identification_report.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "io/mass_record.hpp"
#include "report/json_write.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::report {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Json principal_json(const Eigen::Matrix3d& inertia) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia);
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) *= -1.0;
  Json j;
  j["principal_moments"] = vec(eig.eigenvalues());
  j["principal_axes"] = {vec(axes.col(0)), vec(axes.col(1)), vec(axes.col(2))};
  return j;
}

// The spec's record of the mean, with `std` (over the sets) when there are two or more.
Json mean_json(const identify::MassSummary& s) {
  fe::MassProperties mean;
  mean.mass = s.mass.mean;
  std::array<double, 6> J{};
  for (int i = 0; i < 3; ++i) mean.cog(i) = s.components[static_cast<size_t>(i)].mean;
  for (int i = 0; i < 6; ++i) J[static_cast<size_t>(i)] = s.components[static_cast<size_t>(i + 3)].mean;
  mean.inertia = rig::inertia_tensor(J);
  std::optional<io::MassRecordStd> sd;
  if (s.components[0].std) {
    io::MassRecordStd d;
    d.mass = s.mass.std.value_or(0.0);
    for (int i = 0; i < 3; ++i) d.cog[static_cast<size_t>(i)] = *s.components[static_cast<size_t>(i)].std;
    for (int i = 0; i < 6; ++i) d.inertia[static_cast<size_t>(i)] = *s.components[static_cast<size_t>(i + 3)].std;
    sd = d;
  }
  Json j = io::mass_record_json(mean, sd);
  if (s.components[0].confidence_interval) {
    Json ci = Json::object();
    const auto& names = identify::mass_component_names();
    for (size_t i = 0; i < 9; ++i) ci[names[i]] = *s.components[i].confidence_interval;
    j["confidence_interval_95"] = ci;
  }
  const Json p = principal_json(mean.inertia);
  j["principal_moments"] = p["principal_moments"];
  j["principal_axes"] = p["principal_axes"];
  return j;
}

// The spec's mass-properties record's keys, at the top level of j.
void add_record(Json& j, const fe::MassProperties& record) {
  const Json rec = io::mass_record_json(record);  // named: items() refers into it
  for (const auto& [k, v] : rec.items()) j[k] = v;
}

Json set_json(const std::string& name, const std::vector<std::string>& files, const identify::IdentificationResult& r,
              const fe::MassProperties& record, bool tared) {
  Json j;
  j["name"] = name;
  j["files"] = files;
  add_record(j, record);
  if (tared) j["system"] = io::mass_record_json(r.properties);
  const Json p = principal_json(record.inertia);
  j["principal_moments"] = p["principal_moments"];
  j["principal_axes"] = p["principal_axes"];
  j["positive_definite"] = r.positive_definite;
  j["triangle_inequality"] = r.triangle_inequality;
  j["condition_number"] = r.condition_number;
  j["least_squares_std"] = {{"cog", {r.standard_deviation[0], r.standard_deviation[1], r.standard_deviation[2]}},
                            {"inertia_about_P",
                             {r.standard_deviation[3], r.standard_deviation[4], r.standard_deviation[5],
                              r.standard_deviation[6], r.standard_deviation[7], r.standard_deviation[8]}}};
  j["residual"] = {{"force_rms_n", r.force_residual_rms}, {"moment_rms_nm", r.moment_residual_rms}};
  j["pose_residual"] = {{"rms_m", r.pose_residual_rms}, {"max_m", r.pose_residual_max}};
  j["equations"] = r.equations;
  return j;
}

std::array<double, 9> errors(const fe::MassProperties& p, const fe::MassProperties& ref) {
  const auto a = identify::mass_components(p), b = identify::mass_components(ref);
  std::array<double, 9> e{};
  for (size_t i = 0; i < 9; ++i) e[i] = a[i] - b[i];
  return e;
}

Json test_json(const IdentificationReport& rep, const IdentificationReport::Test& t) {
  Json j;
  j["set"] = rep.set_names[t.set];
  j["file"] = t.file;
  j["observable"] = t.result.observable;
  if (!t.result.observable) {
    j["message"] = t.result.message;
    return j;
  }
  add_record(j, t.record);
  j["condition_number"] = t.result.condition_number;
  return j;
}

Json algorithm_json(const IdentificationReport& rep, const IdentificationReport::Algorithm& a) {
  Json j;
  j["algorithm"] = identify::to_string(a.algorithm);
  const identify::MassSummary s = identify::summarize(a.records);
  j["mean"] = mean_json(s);
  Json sets = Json::array();
  for (size_t k = 0; k < a.records.size(); ++k) {
    sets.push_back(set_json(rep.set_names[k], rep.set_files[k], a.results[k], a.records[k], rep.tare.has_value()));
  }
  j["sets"] = sets;
  if (!a.tests.empty()) {
    Json tests = Json::array();
    for (const auto& t : a.tests) tests.push_back(test_json(rep, t));
    j["tests"] = tests;
  }
  if (rep.reference) {
    Json err = Json::array();
    std::vector<double> zg;
    for (const auto& rec : a.records) {
      err.push_back(errors(rec, *rep.reference));
      zg.push_back(rec.cog.z() - rep.reference->cog.z());
    }
    j["errors"] = {{"components", identify::mass_component_names()}, {"per_set", err}};
    const identify::AccuracyShare share = identify::share_within_accuracy(a.records, *rep.reference, rep.limits);
    j["accuracy_share"] = {{"components", share.component}, {"all", share.all}};
  }
  // The static zG is the system's; with a tare the records are the body's,
  // so the tare comes out of the reference too. An imposed zG has no
  // scatter to plot.
  std::optional<double> static_z;
  if (rep.static_cog_height && rep.options.cog_constraint != identify::CogConstraint::full) {
    static_z = *rep.static_cog_height;
    if (rep.tare) {
      const double m = a.results.front().properties.mass;
      static_z = (m * *static_z - rep.tare->mass * rep.tare->cog.z()) / (m - rep.tare->mass);
    }
  } else if (!rep.static_cog_height && rep.reference) {
    static_z = rep.reference->cog.z();
  }
  if (static_z) {
    const HeightSample sample = height_sample(a);
    std::vector<double> dz;
    for (const double z : sample.z) dz.push_back(z - *static_z);
    Json pts = Json::array();
    for (const auto& p : identify::normal_probability(dz)) {
      pts.push_back({{"value", p.value}, {"probability", p.probability}, {"quantile", p.quantile}});
    }
    j["normal_probability"] = {{"quantity", "zG - static reference zG (m)"}, {"of", sample.of}, {"points", pts}};
  }
  return j;
}

}  // namespace

void IdentificationReport::add(identify::IdentificationAlgorithm a, std::vector<identify::IdentificationResult> results,
                               std::vector<Test> tests) {
  Algorithm alg{a, std::move(results), {}, std::move(tests)};
  auto record = [&](const fe::MassProperties& p) { return tare ? identify::subtract_tare(p, *tare) : p; };
  for (const auto& r : alg.results) alg.records.push_back(record(r.properties));
  for (auto& t : alg.tests) {
    if (t.set >= set_names.size())
      throw std::invalid_argument("identification report: test " + t.file + " of set " + std::to_string(t.set + 1) +
                                  " of " + std::to_string(set_names.size()));
    if (t.result.observable) t.record = record(t.result.properties);
  }
  algorithms.push_back(std::move(alg));
}

std::vector<IdentificationReport::Test> identify_tests(const identify::IdentificationRig& rig,
                                                       const std::vector<const rig::Record*>& histories,
                                                       const std::vector<std::string>& files, std::size_t index,
                                                       const identify::IdentificationOptions& options) {
  if (files.size() != histories.size())
    throw std::invalid_argument("identify_tests: " + std::to_string(files.size()) + " file names for " +
                                std::to_string(histories.size()) + " histories");
  std::vector<IdentificationReport::Test> tests;
  if (histories.size() < 2) return tests;
  for (size_t h = 0; h < histories.size(); ++h) {
    IdentificationReport::Test t;
    t.set = index;
    t.file = files[h];
    try {
      t.result = identify::identify(rig, {histories[h]}, options);
    } catch (const rig::RecordError& e) {  // e.g. a history shorter than the window alone
      t.result.observable = false;
      t.result.message = e.what();
    }
    tests.push_back(std::move(t));
  }
  return tests;
}

HeightSample height_sample(const IdentificationReport::Algorithm& a) {
  HeightSample tests{{}, "tests"}, sets{{}, "sets"};
  for (const auto& t : a.tests)
    if (t.result.observable && std::isfinite(t.record.cog.z())) tests.z.push_back(t.record.cog.z());
  for (const auto& r : a.records)
    if (std::isfinite(r.cog.z())) sets.z.push_back(r.cog.z());
  return tests.z.size() >= 2 && tests.z.size() > sets.z.size() ? tests : sets;
}

nlohmann::ordered_json IdentificationReport::json() const {
  Json j;
  j["rig"] = rig;
  j["algorithm"] = algorithms.size() > 1 ? "both" : identify::to_string(algorithms.front().algorithm);
  j["what"] = tare ? "body (tare subtracted)" : "system on the rods (carrying frame + body)";
  j["options"] = {{"differentiation",
                   {{"method", "savitzky-golay"},
                    {"window_s", options.differentiation.window_s},
                    {"degree", options.differentiation.degree}}},
                  {"equation_rate_hz", options.equation_rate_hz},
                  {"cog_constraint", options.cog_constraint == identify::CogConstraint::none       ? "none"
                                     : options.cog_constraint == identify::CogConstraint::in_plane ? "in_plane"
                                                                                              : "full"}};
  if (tare) j["tare"] = io::mass_record_json(*tare);
  if (reference) j["reference"] = io::mass_record_json(*reference);
  // The primary result is the last algorithm run: flexible when both ran.
  const Json primary = algorithm_json(*this, algorithms.back());
  for (const auto& [k, v] : primary.items()) {
    if (k != "algorithm") j[k] = v;
  }
  if (algorithms.size() > 1) {
    Json all;
    for (const auto& a : algorithms) all[identify::to_string(a.algorithm)] = algorithm_json(*this, a);
    j["algorithms"] = all;
    if (algorithms[0].records.size() >= 2) {
      const auto tests = identify::compare_algorithms(algorithms[0].records, algorithms[1].records);
      Json cmp = Json::array();
      const auto& names = identify::mass_component_names();
      for (size_t i = 0; i < 9; ++i) {
        cmp.push_back({{"component", names[i]},
                       {"t", finite_or_null(tests[i].t)},
                       {"degrees_of_freedom", tests[i].degrees_of_freedom},
                       {"p_value", tests[i].p_value},
                       {"significant", tests[i].significant}});
      }
      j["comparison"] = {{"test", "Welch t, two-sided, alpha 0.05, rigid vs flexible"}, {"components", cmp}};
    }
  }
  return j;
}

std::string IdentificationReport::table() const {
  std::string out;
  char line[512];
  for (const auto& a : algorithms) {
    std::snprintf(line, sizeof line, "%s algorithm, %s\n", identify::to_string(a.algorithm),
                  tare ? "body (tare subtracted)" : "system on the rods");
    out += line;
    std::snprintf(line, sizeof line, "%-10s %9s %9s %9s %9s %9s %9s %8s %8s %8s %8s\n", "set", "xG [mm]", "yG [mm]",
                  "zG [mm]", "Jxx", "Jyy", "Jzz", "Jxy", "Jxz", "Jyz", "cond");
    out += line;
    auto row = [&](const std::string& name, const std::array<double, 9>& c, const std::string& tail) {
      std::snprintf(line, sizeof line, "%-10s %9.2f %9.2f %9.2f %9.1f %9.1f %9.1f %8.1f %8.1f %8.1f %s\n",
                    name.substr(0, 10).c_str(), 1e3 * c[0], 1e3 * c[1], 1e3 * c[2], c[3], c[4], c[5], c[6], c[7], c[8],
                    tail.c_str());
      out += line;
    };
    for (size_t k = 0; k < a.records.size(); ++k) {
      char cond[32];
      std::snprintf(cond, sizeof cond, "%8.3g", a.results[k].condition_number);
      row(std::filesystem::path(set_names[k]).filename().string(), identify::mass_components(a.records[k]), cond);
    }
    const identify::MassSummary s = identify::summarize(a.records);
    std::array<double, 9> mean{}, sd{};
    for (size_t i = 0; i < 9; ++i) {
      mean[i] = s.components[i].mean;
      sd[i] = s.components[i].std.value_or(NAN);
    }
    row("mean", mean, "");
    if (a.records.size() >= 2) row("std", sd, "");
    if (reference) {
      std::array<double, 9> e{};
      for (size_t i = 0; i < 9; ++i) e[i] = mean[i] - identify::mass_components(*reference)[i];
      row("mean-ref", e, "");
      const auto share = identify::share_within_accuracy(a.records, *reference, limits);
      std::snprintf(line, sizeof line, "inside the rig's accuracy: %.0f %% of the sets (all nine components)\n",
                    100 * share.all);
      out += line;
    }
    out += "(CoG in mm, inertia about the CoG in kg m^2, products negative integrals)\n";
  }
  return out;
}

}  // namespace rigflex::report
