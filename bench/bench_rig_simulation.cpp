// Benchmark: virtual measurements of a rig (issue 4). One history of the
// release protocol (raised-cosine push, then a 15 s free swing sampled at the
// sensors' rate) and a full virtual measurement (6 histories), against real
// time and against the floor: the cost of the right-hand side evaluations
// the integrator made, each timed alone.
// Targets (issue 4): a 15 s history of the large flexible rig at 500 Hz at
// least 500x faster than real time; 6 histories under 0.5 s.
//
// Usage:
//   bench_rig_simulation RIG.yaml [RIG.yaml ...] [--duration 15] [--histories 6] [--repeat 3]
// Prints a markdown table on stdout.
//
// Measurement notes:
//   * wall times, best of --repeat; the equilibrium is computed once, outside
//     the timings (`rigflex simulate` does the same once per run);
//   * "dF N" and "dangle rad": the largest difference of the noise-free
//     signals (load cells; encoders) from a reference run (CVODE BDF2 at
//     1e-8 relative, 1e-12 m), to read against the sensors' noise;
//   * "rhs us" is one evaluation of the equations of motion (generalized
//     forces and accelerations) at the equilibrium, averaged over 2e4 calls;
//     "rhs share" = rhs evaluations x rhs us / history time.
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_cli.hpp"
#include "io/rig_reader.hpp"
#include "rig/equilibrium.hpp"
#include "rig/linearization.hpp"
#include "rig/simulation.hpp"

namespace {

using namespace rigflex;
using bench::clock_type;
using bench::seconds_since;

struct Options {
  std::vector<std::string> rigs;
  double duration = 15.0;
  int histories = 6;
  int repeat = 3;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] { return bench::option_value(argc, argv, i); };
    if (a == "--duration") {
      o.duration = std::stod(value());
    } else if (a == "--histories") {
      o.histories = std::stoi(value());
    } else if (a == "--repeat") {
      o.repeat = std::stoi(value());
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a);
    } else {
      o.rigs.push_back(a);
    }
  }
  if (o.rigs.empty()) throw std::invalid_argument("usage: bench_rig_simulation RIG.yaml [...] [--duration S]");
  return o;
}

double rhs_microseconds(const rig::RigSystem& rig, const rig::Configuration& c) {
  const rig::Velocity v = rig.at_rest();
  constexpr int calls = 20000;
  double sink = 0;
  const auto t0 = clock_type::now();
  for (int k = 0; k < calls; ++k) {
    const Eigen::VectorXd Q = rig.generalized_forces(c, v, 0.0);
    sink += rig.accelerations(v, Q)(0);
  }
  const double us = 1e6 * seconds_since(t0) / calls;
  if (sink == 12345.678) std::fprintf(stderr, " ");  // keeps the loop
  return us;
}

// Noise-free signals with the model's integrator settings, or (reference)
// with CVODE's BDF2 at 1e-8 relative and 1e-12 m.
rig::Record noise_free_history(rig::RigModel model, bool reference, const rig::HistoryRequest& req) {
  model.sensors.force_noise_n = model.sensors.angle_noise_rad = model.sensors.force_resolution_n = 0.0;
  model.sensors.encoder_bits = 0;
  if (reference) {
    model.simulation.method = rig::IntegrationMethod::bdf;
    model.simulation.max_order = 2;
    model.simulation.relative_tolerance = 1e-8;
    model.simulation.position_tolerance = 1e-12;
  }
  const rig::RigSystem rig(model);
  const rig::Equilibrium eq = rig::static_equilibrium(rig);
  if (!eq.converged) throw std::runtime_error(eq.message);
  return rig::simulate_history(rig, eq.configuration, req);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::printf("| rig | states | history s | x real time | steps | newton its | LU setups | rhs evals | jac evals | "
                "rhs us | rhs share | %d histories s | dF N | dangle rad | noise N, rad |\n",
                o.histories);
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& file : o.rigs) {
      const rig::RigModel model = io::read_rig(file);
      const rig::RigSystem rig(model);
      const rig::Linearization lin = rig::linearize(rig);
      const rig::Configuration& eq = lin.equilibrium.configuration;
      rig::HistoryRequest req;
      req.duration_s = o.duration;
      req.push = rig::draw_push(rig, 1, 1, 1);
      req.noise_seed = rig::noise_seed(1, 1, 1);
      req.linearization = &lin;
      double best_history = std::numeric_limits<double>::infinity();
      rig::IntegratorStatistics stats;
      for (int r = 0; r < o.repeat; ++r) {
        const auto t0 = clock_type::now();
        rig::simulate_history(rig, eq, req, &stats);
        best_history = std::min(best_history, seconds_since(t0));
      }
      rig::MeasurementOptions mo;
      mo.histories = o.histories;
      mo.duration_s = o.duration;
      double best_set = std::numeric_limits<double>::infinity();
      for (int r = 0; r < o.repeat; ++r) {
        const auto t0 = clock_type::now();
        rig::simulate_measurement(rig, mo);
        best_set = std::min(best_set, seconds_since(t0));
      }
      const double rhs_us = rhs_microseconds(rig, eq);
      const double simulated = o.duration + (req.push ? req.push->duration_s : 0.0);
      const rig::Record h1 = noise_free_history(model, false, req), h2 = noise_free_history(model, true, req);
      const double dF = (h1.force - h2.force).cwiseAbs().maxCoeff();
      const double da = std::max((h1.alpha - h2.alpha).cwiseAbs().maxCoeff(), (h1.beta - h2.beta).cwiseAbs().maxCoeff());
      std::printf("| %s | %d | %.3f | %.0f | %ld | %ld | %ld | %ld | %ld | %.2f | %.2f | %.3f | %.2g | %.2g | %.2g, %.2g |\n",
                  model.name.c_str(),
                  rig.state_size(), best_history, simulated / best_history, stats.steps, stats.newton_iterations,
                  stats.linear_setups, stats.rhs_evaluations,
                  stats.jacobian_evaluations, rhs_us, stats.rhs_evaluations * rhs_us * 1e-6 / best_history, best_set, dF, da,
                  model.sensors.force_noise_n, model.sensors.angle_noise_rad);
      std::fflush(stdout);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_rig_simulation: %s\n", e.what());
    return 1;
  }
}
