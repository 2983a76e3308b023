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
// check: what a user waits for) and prints a table: the fill measure the
// automatic rule reads, the time per block size, the fastest, the automatic
// choice and its time over the fastest. One OpenBLAS thread (set
// OPENBLAS_NUM_THREADS=1 as bench/run_plate_bench.sh does) keeps the
// factorizations comparable on a shared machine.
//
// Sample run (2 cores, shared):
//   OPENBLAS_NUM_THREADS=1 build/bench/bench_block_size --models plate:10k,quad8:30k --repeat 1
//   | model | DOFs | nnz(L)/n | basis | fill ratio | block 1 s | block 4 s | fastest | automatic | automatic/fastest |
//   | plate:10k | 10086 | 65 | 40 | 1.62 | 0.17 | 0.19 | 1 | 1 | 1.00 |
//   | quad8:30k | 29280 | 114 | 40 | 2.85 | 1.08 | 0.92 | 4 | 4 | 1.00 |
//
// Usage: bench_block_size [--models kind:size,...] [--blocks 1,4] [--modes 20] [--repeat 2]
//   kinds: plate (MITC4), quad8 (8-node shells), girder (MITC4 box girder), lattice (3D beam lattice),
//          ladder (beam ladder)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_cli.hpp"
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
    else throw std::invalid_argument("unknown option " + a);
  }
  if (o.blocks.empty() || o.repeat < 1 || o.modes < 1) throw std::invalid_argument("nothing to run");
  for (int b : o.blocks)
    if (b < 1) throw std::invalid_argument("--blocks takes block sizes >= 1");
  return o;
}

void add_steel_tube(fe::Model& m) {
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850.0};
  fe::BeamSection s;
  s.name = "tube";
  s.material = "steel";
  s.shape = fe::SectionShape::Box;
  s.width = 0.1;
  s.height = 0.1;
  s.wall = 0.005;
  m.beam_sections["tube"] = s;
}

void clamp(fe::Model& m, fe::NodeId node) { m.supports.push_back({"clamp", node, {true, true, true, true, true, true}}); }

// k x k x k nodes 0.5 m apart joined by one beam per edge along x, y and z;
// the bottom layer clamped.
fe::Model beam_lattice(int k) {
  fe::Model m;
  add_steel_tube(m);
  fe::NodeMerger merger(m);
  const double h = 0.5;
  auto member = [&](const fe::Vec3& a, const fe::Vec3& b) {
    fe::MemberSpec s;
    s.id = "bar";
    s.from = a;
    s.to = b;
    s.section = "tube";
    s.orientation = (b - a).normalized().cross(fe::Vec3::UnitX()).norm() > 0.5 ? fe::Vec3::UnitX() : fe::Vec3::UnitY();
    return fe::mesh_member(m, merger, s);
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) {
        const fe::Vec3 p(i * h, j * h, l * h);
        if (i + 1 < k) member(p, p + fe::Vec3(h, 0, 0));
        if (j + 1 < k) member(p, p + fe::Vec3(0, h, 0));
        if (l + 1 < k) {
          const std::vector<fe::NodeId> ids = member(p, p + fe::Vec3(0, 0, h));
          if (l == 0) clamp(m, ids.front());
        }
      }
  return m;
}

fe::MemberSpec ladder_member(const fe::Vec3& from, const fe::Vec3& to) {
  fe::MemberSpec s;
  s.id = "ladder";
  s.from = from;
  s.to = to;
  s.elements = 4;
  s.section = "tube";
  s.orientation = fe::Vec3::UnitZ();
  return s;
}

// Two parallel rails 1 m apart with a rung every metre, 4 elements per rail
// bay and per rung, clamped at one end: a long, banded structure.
fe::Model beam_ladder(int bays) {
  fe::Model m;
  add_steel_tube(m);
  fe::NodeMerger merger(m);
  for (int b = 0; b <= bays; ++b) {
    const fe::Vec3 left(b, 0, 0), right(b, 1, 0);
    const std::vector<fe::NodeId> ids = fe::mesh_member(m, merger, ladder_member(left, right));
    if (b == 0) clamp(m, ids.front()), clamp(m, ids.back());
    if (b == bays) break;
    for (const double y : {0.0, 1.0}) {
      fe::mesh_member(m, merger, ladder_member(fe::Vec3(b, y, 0), fe::Vec3(b + 1, y, 0)));
    }
  }
  return m;
}

// A 0.4 m x 0.6 m box girder of 8 mm shells, 8 x 8 elements around the
// section, `along` elements over 10 m, clamped at one end through its
// reference node: the closed shell section rig frames are built from.
fe::Model shell_girder(int along) {
  fe::Model m;
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850.0};
  fe::NodeMerger merger(m);
  fe::BoxGirderSpec g;
  g.id = "girder";
  g.from = fe::Vec3(0, 0, 0);
  g.to = fe::Vec3(10, 0, 0);
  g.width = 0.4;
  g.height = 0.6;
  g.web_thickness = g.flange_thickness = 0.008;
  g.material = "steel";
  g.n_along = along;
  g.n_width = g.n_height = 8;
  const fe::BoxGirderNodes ends = fe::mesh_box_girder(m, merger, g);
  clamp(m, *ends.start_reference);
  return m;
}

// kind:size -> a model of about `size` DOFs.
fe::Model build(const std::string& spec, std::string& kind) {
  const size_t colon = spec.find(':');
  if (colon == std::string::npos) throw std::invalid_argument("model '" + spec + "' is not kind:size");
  kind = spec.substr(0, colon);
  const double dofs = static_cast<double>(bench::parse_size(spec.substr(colon + 1)));
  if (kind == "plate") return bench::clamped_plate(bench::divisions_for(static_cast<long>(dofs)));
  // 8-node grid of n x n elements: (3 n^2 + 2 n) nodes, 6 DOFs each.
  if (kind == "quad8") return bench::clamped_plate(static_cast<int>(std::lround(std::sqrt(dofs / 18.0))), true);
  if (kind == "lattice") return beam_lattice(static_cast<int>(std::lround(std::cbrt(dofs / 6.0))));
  // 32 nodes per section ring, 6 DOFs each.
  if (kind == "girder") return shell_girder(static_cast<int>(std::lround(dofs / 192.0)));
  // per bay: 2 x 4 rail nodes + 3 interior rung nodes = 11 nodes, 66 DOFs.
  if (kind == "ladder") return beam_ladder(static_cast<int>(std::lround(dofs / 66.0)));
  throw std::invalid_argument("unknown model kind '" + kind + "' (plate, quad8, girder, lattice, ladder)");
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
  table << "| model | DOFs | nnz(L)/n | basis | fill ratio |";
  for (int b : o.blocks) table << " block " << b << " s |";
  table << " fastest | automatic | automatic/fastest |\n|---|---:|---:|---:|---:|";
  for (size_t i = 0; i < o.blocks.size(); ++i) table << "---:|";
  table << "---:|---:|---:|\n";
  for (const std::string& spec : o.models) {
    std::string kind;
    const fe::Model model = build(spec, kind);
    const fe::AssembledSystem sys = fe::assemble(model);
    const Eigen::Index n = sys.K.rows();
    std::cerr << "== " << spec << ": " << n << " DOFs (load " << bench::loadavg() << ")\n";

    linalg::EigenOptions eo;
    eo.count = o.modes;
    eo.method = linalg::EigenMethod::lanczos;
    eo.subspace = o.subspace;
    linalg::SparseCholesky probe;
    const linalg::PencilFactorization pencil = linalg::factorize_pencil(sys.K, sys.M, std::nullopt, probe);
    if (!pencil.ok) throw std::runtime_error(spec + ": " + pencil.message);
    const double nnz = probe.statistics().factor_nnz;
    const int automatic = linalg::automatic_block_size(n, nnz, eo.count);
    const double ratio = linalg::block_fill_ratio(n, nnz, eo.count);

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
          << eo.resolved_subspace(n, 1) << " | " << fmt(ratio, 2) << " |";
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
