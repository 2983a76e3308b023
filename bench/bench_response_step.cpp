// Benchmark: the integration step of the model predictions that compare and
// diagnose fit (diagnose/model_response.hpp). Each fit simulates every
// record hundreds of times, so the step sets diagnose's speed; what it must
// resolve is the swing band (diagnose/swing_band.hpp), where the residual is
// compared in units of the band's noise. For each rig: records simulated
// with sensor noise, the swing state fitted with a fine-step model (every
// mode up to --reference-hz resolved), then the band residual of the same
// state predicted at each candidate step, against the fine one.
//
// Usage:
//   bench_response_step RIG.yaml [RIG.yaml ...] [--histories 2] [--resolve 0,16,10]
//                       [--reference-hz 100] [--repeat 3]
// --resolve lists simulation.resolve_hz values (0: the model's default).
// Prints a markdown table on stdout:
//   * "step ms": generalized-alpha's step (it divides the sample interval);
//   * "band error": RMS over every band sample of the difference of the
//     noise-weighted band residuals from the fine step's (1 = the band's
//     noise; the fits' gates sit at 4 x the noise in the sum of squares);
//   * "max": the largest single difference, same units;
//   * "s per prediction": wall time of one record's prediction, best of --repeat;
//   * "data misfit": RMS of the fine step's noise-weighted band residual
//     against the records (1 = the records are the model plus noise; above
//     that, the records' own integration error: the rig file's
//     `simulation` block decides how they are simulated).
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bench/bench_cli.hpp"
#include "diagnose/history_comparison.hpp"
#include "diagnose/model_response.hpp"
#include "io/rig_reader.hpp"
#include "rig/generalized_alpha.hpp"
#include "rig/simulation.hpp"

namespace {

using namespace rigflex;
using bench::clock_type;
using bench::seconds_since;

struct Options {
  std::vector<std::string> rigs;
  int histories = 2;
  std::vector<double> resolve{0.0, 16.0, 10.0};
  double reference_hz = 100.0;
  int repeat = 3;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] { return bench::option_value(argc, argv, i); };
    if (a == "--histories") {
      o.histories = std::stoi(value());
    } else if (a == "--resolve") {
      o.resolve.clear();
      for (const std::string& x : bench::split(value())) o.resolve.push_back(std::stod(x));
    } else if (a == "--reference-hz") {
      o.reference_hz = std::stod(value());
    } else if (a == "--repeat") {
      o.repeat = std::stoi(value());
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a);
    } else {
      o.rigs.push_back(a);
    }
  }
  if (o.rigs.empty()) throw std::invalid_argument("usage: bench_response_step RIG.yaml [RIG.yaml ...] [options]");
  return o;
}

// The model as the fits predict it - generalized-alpha, whatever simulated
// the records - resolving modes up to resolve_hz (0: the model's default).
diagnose::ResponseModel model_resolving(rig::RigModel m, double resolve_hz) {
  m.simulation.method = rig::IntegrationMethod::generalized_alpha;
  m.simulation.resolve_hz = resolve_hz;
  return diagnose::ResponseModel(m);
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  std::printf("| rig | data | resolve Hz | step ms | band error (noise) | max | s per prediction | data misfit |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const auto& file : o.rigs) {
    const rig::RigModel model = io::read_rig(file);
    rig::MeasurementOptions mo;
    mo.histories = o.histories;
    const auto records = rig::simulate_measurement(rig::RigSystem(model), mo).front();
    const diagnose::ResponseModel fine = model_resolving(model, o.reference_hz);
    std::vector<diagnose::HistoryComparison> ref;
    std::vector<Eigen::VectorXd> r_ref;
    for (const auto& r : records) {
      ref.push_back(diagnose::compare_history(fine, r, file, {}));
      r_ref.push_back(diagnose::band_residual(fine, ref.back().fit.state, ref.back().target));
    }
    const std::string name = std::filesystem::path(file).parent_path().filename().string() + "/" +
                             std::filesystem::path(file).stem().string();
    double misfit = 0, samples = 0;
    for (const auto& r : r_ref) misfit += r.squaredNorm(), samples += static_cast<double>(r.size());
    char data[64];
    if (model.simulation.method == rig::IntegrationMethod::bdf) {
      std::snprintf(data, sizeof data, "BDF, rtol %.0e", model.simulation.relative_tolerance);
    } else {
      std::snprintf(data, sizeof data, "generalized-alpha");
    }
    for (double hz : o.resolve) {
      const diagnose::ResponseModel m = model_resolving(model, hz);
      const double dt = ref.front().target.record.step_s;
      const double step = rig::generalized_alpha_step(m.linearization, 1.0 / dt, m.resolve_hz);
      double sum = 0, count = 0, worst = 0, best = HUGE_VAL;
      for (size_t j = 0; j < records.size(); ++j) {
        Eigen::VectorXd r;
        for (int k = 0; k < o.repeat; ++k) {
          const auto t0 = clock_type::now();
          r = diagnose::band_residual(m, ref[j].fit.state, ref[j].target);
          best = std::min(best, seconds_since(t0));
        }
        const Eigen::VectorXd d = r - r_ref[j];
        sum += d.squaredNorm();
        count += static_cast<double>(d.size());
        worst = std::max(worst, d.cwiseAbs().maxCoeff());
      }
      std::printf("| %s | %s | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g |\n", name.c_str(), data, m.resolve_hz,
                  1e3 * step, std::sqrt(sum / count), worst, best, std::sqrt(misfit / samples));
      std::fflush(stdout);
    }
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "bench_response_step: " << e.what() << "\n";
  return 1;
}
