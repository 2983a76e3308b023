// Lanczos block size: which one is fastest, and does the automatic choice
// (EigenOptions::block_size = 0, see automatic_block_size in
// linalg/eigen_solver.hpp) pick it?
//
// For models of different fill -- clamped MITC4 and 8-node plates (2D fill),
// a long shell box girder (a folded plate, as rig frames are built),
// a clamped 3D lattice of beams (3D fill, the heaviest per DOF) and a long
// beam ladder (banded, the lightest) -- the program solves the same
// eigenproblem with each block size asked for, keeps the best wall time of
// --repeat runs of solve_lanczos (factorization, iteration, Rayleigh-Ritz and
// check: what a user waits for) and prints a table: the words one
// application streams (nnz(L) + n x basis, what the automatic rule reads),
// the time per block size, the fastest, the automatic choice and its time
// over the fastest. One OpenBLAS thread (set OPENBLAS_NUM_THREADS=1 as
// bench/run_plate_bench.sh does) keeps the factorizations comparable on a
// shared machine. --no-verify turns the multiplicity check off, to measure
// what it costs.
//
// Sample run (2 cores, shared; the table's columns: model, DOFs, nnz(L)/n,
// basis, words per application in millions, block 1 s, block 4 s, fastest,
// automatic, automatic/fastest):
//   OPENBLAS_NUM_THREADS=1 build/bench/bench_block_size --models plate:10k,plate:30k --repeat 3
//   | plate:10k | 10086 | 65 | 40 | 1.06 | 0.18 | 0.27 | 1 | 1 | 1.00 |
//   | plate:30k | 30246 | 81 | 40 | 3.67 | 1.33 | 0.94 | 4 | 4 | 1.00 |
//
// Usage: bench_block_size [--models kind:size,...] [--blocks 1,4] [--modes 20] [--repeat 2] [--subspace M]
//                         [--no-verify]
//   kinds: plate (MITC4), quad8 (8-node shells; quad8c: centres condensed), girder (MITC4 box girder),
//          lattice (3D beam lattice), ladder (beam ladder)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_cli.hpp"
#include "bench/bench_models.hpp"
#include "bench/plate_model.hpp"
#include "fe/assembly.hpp"
#include "fe/meshers.hpp"
#include "fe/model.hpp"
#include "fe/node_merger.hpp"
#include "linalg/eigen_solver.hpp"

namespace {

using namespace rigflex;
using bench::clock_type;
using bench::seconds_since;

struct Options {
  std::vector<std::string> models = {"plate:10k",   "plate:30k",  "plate:50k",   "plate:100k",  "quad8:30k",
                                     "quad8:100k",  "girder:30k", "girder:100k", "lattice:10k", "lattice:30k",
                                     "lattice:60k", "ladder:30k", "ladder:200k"};
  std::vector<int> blocks = {1, 4};
  int modes = 20;
  int repeat = 2;
  int subspace = 0;  // 0: the solver's automatic basis
  bool verify = true;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--models") o.models = bench::split(bench::option_value(argc, argv, i));
    else if (a == "--blocks") {
      o.blocks.clear();
      for (const std::string& b : bench::split(bench::option_value(argc, argv, i))) o.blocks.push_back(std::stoi(b));
    } else if (a == "--modes") o.modes = std::stoi(bench::option_value(argc, argv, i));
    else if (a == "--repeat") o.repeat = std::stoi(bench::option_value(argc, argv, i));
    else if (a == "--subspace") o.subspace = std::stoi(bench::option_value(argc, argv, i));
    else if (a == "--no-verify")
      o.verify = false;
    else throw std::invalid_argument("unknown option " + a);
  }
  if (o.blocks.empty() || o.repeat < 1 || o.modes < 1) throw std::invalid_argument("nothing to run");
  for (int b : o.blocks)
    if (b < 1) throw std::invalid_argument("--blocks takes block sizes >= 1");
  return o;
}

std::string fmt(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  std::ostringstream table;
  table << "| model | DOFs | nnz(L)/n | basis | words per application, M |";
  for (int b : o.blocks) table << " block " << b << " s |";
  table << " fastest | automatic | automatic/fastest |\n|---|---:|---:|---:|---:|";
  for (size_t i = 0; i < o.blocks.size(); ++i) table << "---:|";
  table << "---:|---:|---:|\n";
  for (const std::string& spec : o.models) {
    std::string kind;
    const fe::Model model = bench::model_of(spec, kind);
    const fe::AssembledSystem sys = fe::assemble(model);
    const Eigen::Index n = sys.K.rows();
    std::cerr << "== " << spec << ": " << n << " DOFs (load " << bench::loadavg() << ")\n";

    linalg::EigenOptions eo;
    eo.count = o.modes;
    eo.method = linalg::EigenMethod::lanczos;
    eo.subspace = o.subspace;
    eo.verify_multiplicities = o.verify;
    linalg::SparseCholesky probe;
    const linalg::PencilFactorization pencil = linalg::factorize_pencil(sys.K, sys.M, std::nullopt, probe);
    if (!pencil.ok) throw std::runtime_error(spec + ": " + pencil.message);
    const double nnz = probe.statistics().factor_nnz;
    const int automatic = linalg::automatic_block_size(n, nnz, eo.count);
    const double words = linalg::application_words(n, nnz, eo.count);

    std::vector<double> best(o.blocks.size(), 0);
    for (int rep = 0; rep < o.repeat; ++rep)
      for (size_t i = 0; i < o.blocks.size(); ++i) {
        eo.block_size = o.blocks[i];
        const auto t0 = clock_type::now();
        const linalg::EigenResult r = linalg::solve_lanczos(sys.K, sys.M, eo);
        const double t = seconds_since(t0);
        if (!r.converged) throw std::runtime_error(spec + ": block " + std::to_string(o.blocks[i]) + ": " + r.message);
        if (r.backward_errors.maxCoeff() > 1e-9 || r.orthogonality_error > 1e-9)
          throw std::runtime_error(spec + ": block " + std::to_string(o.blocks[i]) + ": pairs fail the check");
        if (rep == 0 || t < best[i]) best[i] = t;
        std::cerr << "   block " << o.blocks[i] << ": " << t << " s, " << r.operator_applications
                  << " applications, " << r.restarts << " restarts\n";
      }
    const size_t fastest = static_cast<size_t>(std::min_element(best.begin(), best.end()) - best.begin());
    const auto chosen = std::find(o.blocks.begin(), o.blocks.end(), automatic);
    table << "| " << spec << " | " << n << " | " << fmt(nnz / static_cast<double>(n), 0) << " | "
          << eo.resolved_subspace(n, 1) << " | " << fmt(words / 1e6, 2) << " |";
    for (double t : best) table << " " << fmt(t, 2) << " |";
    table << " " << o.blocks[fastest] << " | " << automatic << " | "
          << (chosen == o.blocks.end() ? std::string("not run")
                                       : fmt(best[static_cast<size_t>(chosen - o.blocks.begin())] / best[fastest], 2))
          << " |\n";
  }
  std::cout << "\n### Lanczos block size, " << o.modes << " modes, best of " << o.repeat << "\n\n" << table.str();
  return 0;
} catch (const std::exception& e) {
  std::cerr << "bench_block_size: " << e.what() << "\n";
  return 1;
}
