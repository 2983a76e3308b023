// Benchmark: Guyan and Craig-Bampton reduction of the clamped steel plate of
// bench_plate_modes (MITC4, 1 m x 1 m x 10 mm) onto 4 joint nodes at the
// quarter points (3 translations each: 12 interface DOFs), against the eigen
// solve alone (the 20 lowest modes of the full plate by solve_lanczos).
// Target (issue 3): at 1M DOFs, Guyan and Craig-Bampton with 20 modes each
// within 1.3x of the eigen solve (one factorization of K_ii serves the
// constraint modes and the fixed-interface modes).
//
// Usage:
//   bench_plate_reduction [--sizes 10k,100k,1M] [--modes 20] [--repeat 1]
// Prints a markdown table on stdout, progress on stderr.
//
// Measurement notes:
//   * times are wall times of one call each: linalg::solve_lanczos (its
//     factorization of K - sigma M included) and reduction::reduce_component
//     (partition, factorization of K_ii, the 12 constraint-mode solves, the
//     Lanczos for the fixed-interface modes, the projection, and the basis T
//     kept for expansion as reduce_frame keeps it); assembly excluded.
//   * "peak" = VmHWM during the call (reset before it through
//     /proc/self/clear_refs) minus VmRSS before it: the call's own memory.
//   * best of --repeat runs for the times; the machine is shared.
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_cli.hpp"
#include "bench/plate_model.hpp"
#include "fe/assembly.hpp"
#include "reduction/component_modes.hpp"
#include "linalg/eigen_solver.hpp"

namespace {

using namespace rigflex;
using bench::clock_type;
using bench::seconds_since;

struct Options {
  std::vector<long> sizes{10000, 100000};
  int modes = 20;
  int repeat = 1;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] { return bench::option_value(argc, argv, i); };
    if (a == "--sizes") {
      o.sizes = bench::parse_sizes(value());
    } else if (a == "--modes") {
      o.modes = std::stoi(value());
    } else if (a == "--repeat") {
      o.repeat = std::max(1, std::stoi(value()));
    } else {
      throw std::invalid_argument("unknown option " + a + " (see the head of bench_plate_reduction.cpp)");
    }
  }
  return o;
}

fe::NodeId nearest_node(const fe::Model& m, const fe::Vec3& x) {
  fe::NodeId best = m.nodes.front().id;
  double d = std::numeric_limits<double>::max();
  for (const auto& n : m.nodes) {
    if ((n.x - x).squaredNorm() < d) {
      d = (n.x - x).squaredNorm();
      best = n.id;
    }
  }
  return best;
}

struct Timed {
  double seconds = std::numeric_limits<double>::max();
  double peak_mb = 0;
};

// Best time of `repeat` calls of f, and the largest peak memory among them.
template <class F>
Timed measure(int repeat, F f) {
  Timed t;
  for (int r = 0; r < repeat; ++r) {
    bench::reset_peak_rss();
    const long rss0 = bench::status_kb("VmRSS:");
    const auto t0 = clock_type::now();
    f();
    t.seconds = std::min(t.seconds, seconds_since(t0));
    t.peak_mb = std::max(t.peak_mb, (bench::status_kb("VmHWM:") - rss0) / 1024.0);
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::printf("load average at start: %s\n\n", bench::loadavg().c_str());
    std::printf("| DOFs | eigen %d modes [s] | Guyan [s] | Guyan / eigen | CB-%d [s] | CB / eigen | eigen peak [MB] | "
                "Guyan peak [MB] | CB peak [MB] | factor K_ii [MB] |\n",
                o.modes, o.modes);
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (long size : o.sizes) {
      const int n = bench::divisions_for(size);
      std::fprintf(stderr, "plate %d x %d: meshing and assembling\n", n, n);
      const fe::Model model = bench::clamped_plate(n);
      const fe::AssembledSystem sys = fe::assemble(model);
      std::vector<Eigen::Index> boundary;
      for (double x : {0.25, 0.75})
        for (double y : {0.25, 0.75}) {
          const fe::NodeId id = nearest_node(model, {x, y, 0});
          for (int d = 0; d < 3; ++d) boundary.push_back(sys.dofs.full_to_free[model.node_index(id) * 6 + size_t(d)]);
        }

      std::fprintf(stderr, "  eigen solve (%ld DOFs)\n", static_cast<long>(sys.K.rows()));
      linalg::EigenOptions eo;
      eo.count = o.modes;
      bool converged = true;
      const Timed eigen = measure(o.repeat, [&] { converged &= linalg::solve_lanczos(sys.K, sys.M, eo).converged; });

      std::fprintf(stderr, "  Guyan\n");
      reduction::ComponentModeOptions g;
      double factor_mb = 0;
      const Timed guyan = measure(o.repeat, [&] {
        const auto r = reduction::reduce_component(sys.K, sys.M, boundary, g);
        converged &= r.ok;
        factor_mb = r.statistics.factor_bytes / (1024.0 * 1024.0);
      });

      std::fprintf(stderr, "  Craig-Bampton, %d modes\n", o.modes);
      reduction::ComponentModeOptions cb;
      cb.method = reduction::ReductionMethod::craig_bampton;
      cb.modes = o.modes;
      const Timed craig = measure(o.repeat, [&] { converged &= reduction::reduce_component(sys.K, sys.M, boundary, cb).ok; });
      if (!converged) throw std::runtime_error("a solve did not converge at " + std::to_string(size) + " DOFs");

      std::printf("| %ld | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.0f | %.0f | %.0f |\n",
                  static_cast<long>(sys.K.rows()), eigen.seconds, guyan.seconds, guyan.seconds / eigen.seconds,
                  craig.seconds, craig.seconds / eigen.seconds, eigen.peak_mb, guyan.peak_mb, craig.peak_mb, factor_mb);
      std::fflush(stdout);
    }
    std::printf("\nload average at end: %s\n", bench::loadavg().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_plate_reduction: %s\n", e.what());
    return 1;
  }
}
