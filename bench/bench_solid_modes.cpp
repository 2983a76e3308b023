// Benchmark: the solid elements on NAFEMS FV52 (verification/nafems_fv52.hpp)
// at the benchmark's meshes and finer, against CalculiX on the same mesh
// (hex8 - C3D8I, hex20 - C3D20, tet10 - C3D10; each cell of a tet10 mesh is
// split in six). Per element and mesh: DOFs, rigflex time (assembly and
// eigen solve of 10 modes, three of them rigid), ccx time (its whole run:
// parsing, assembly, eigen solve), ratio, the largest difference between the
// two over modes 4-10, and every mode's ratio to the NAFEMS target.
//
// Usage:
//   bench_solid_modes [--levels 1,2,4] [--elements hex8,hex20,tet10] [--skip-ccx]
//                     [--workdir /tmp/rigflex-bench-solid] [--keep]
// Level L meshes L times the benchmark's cells in every direction: hex8
// 8x8x3 L, hex20 and tet10 4x4x1 L. Prints a markdown table on stdout,
// progress on stderr.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "reduction/modal_analysis.hpp"
#include "verification/calculix.hpp"
#include "verification/nafems_fv52.hpp"

namespace {

using namespace rigflex;
namespace fs = std::filesystem;

constexpr int kModes = 10;

struct Args {
  std::vector<int> levels{1, 2, 4};
  std::vector<std::string> elements{"hex8", "hex20", "tet10"};
  bool skip_ccx = false, keep = false;
  fs::path workdir = fs::temp_directory_path() / ("rigflex-bench-solid-" + std::to_string(::getpid()));
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto value = [&] { return bench::option_value(argc, argv, i); };
    if (k == "--levels") {
      a.levels.clear();
      for (const std::string& v : bench::split(value())) a.levels.push_back(std::stoi(v));
    } else if (k == "--elements") {
      a.elements = bench::split(value());
    } else if (k == "--skip-ccx") {
      a.skip_ccx = true;
    } else if (k == "--workdir") {
      a.workdir = value();
    } else if (k == "--keep") {
      a.keep = true;
    } else {
      throw std::invalid_argument("unknown option " + k);
    }
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) try {
  const Args args = parse(argc, argv);
  std::printf(
      "| element | mesh | DOFs | rigflex s | ccx s | ccx / rigflex | max diff vs ccx, modes 4-10 |"
      " ratio to target, modes 4-10 |\n|---|---|---|---|---|---|---|---|\n");
  for (const std::string& element : args.elements)
    for (int level : args.levels) {
      const int n = (element == "hex8" ? 8 : 4) * level, nz = (element == "hex8" ? 3 : 1) * level;
      const std::string mesh = std::to_string(n) + "x" + std::to_string(n) + "x" + std::to_string(nz);
      std::fprintf(stderr, "%s %s: rigflex\n", element.c_str(), mesh.c_str());
      const fe::Model model = verification::nafems_fv52(element, n, nz);
      linalg::EigenOptions options;
      options.count = kModes;
      options.shift = -std::pow(2 * M_PI * 10.0, 2);  // below the rigid-body modes
      const auto t0 = bench::clock_type::now();
      const reduction::ModalAnalysis a = reduction::run_modal_analysis(model, options);
      const double ours = bench::seconds_since(t0);
      if (!a.result.converged) throw std::runtime_error(element + " " + mesh + ": " + a.result.message);
      const Eigen::VectorXd f = a.result.frequencies_hz();
      std::string ccx_time = "-", ratio = "-", diff = "-";
      if (!args.skip_ccx) {
        std::fprintf(stderr, "%s %s: ccx\n", element.c_str(), mesh.c_str());
        const fs::path dir = args.workdir / (element + "-" + mesh);
        const verification::CalculixFrequencies c = verification::run_calculix_frequencies(model, kModes, dir);
        double worst = 0;
        for (int k = verification::kFv52RigidModes; k < kModes; ++k)
          worst = std::max(worst, std::abs(c.frequencies_hz.at(static_cast<size_t>(k)) / f(k) - 1));
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.2f", c.wall_seconds);
        ccx_time = buf;
        std::snprintf(buf, sizeof buf, "%.1f", c.wall_seconds / ours);
        ratio = buf;
        std::snprintf(buf, sizeof buf, "%.2g %%", 100 * worst);
        diff = buf;
        if (!args.keep) fs::remove_all(dir);
      }
      std::string ratios;
      for (size_t i = 0; i < verification::kFv52TargetsHz.size(); ++i) {
        char buf[16];
        std::snprintf(
            buf, sizeof buf, "%s%.4f", i ? " " : "",
            f(verification::kFv52RigidModes + static_cast<Eigen::Index>(i)) / verification::kFv52TargetsHz[i]);
        ratios += buf;
      }
      std::printf("| %s | %s | %ld | %.2f | %s | %s | %s | %s |\n", element.c_str(), mesh.c_str(),
                  static_cast<long>(a.system.K.rows()), ours, ccx_time.c_str(), ratio.c_str(), diff.c_str(),
                  ratios.c_str());
      std::fflush(stdout);
    }
  if (!args.keep) fs::remove_all(args.workdir);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_solid_modes: %s\n", e.what());
  return 1;
}
