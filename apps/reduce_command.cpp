// rigflex reduce MODEL.yaml --interface SET [--method guyan|craig-bampton]
//   [--modes N | --cutoff HZ] [--dofs all|translations] [--zeta 0.02] [--zeta-modes 1,3] --out DIR:
// a frame reduced onto its joint DOFs, with damping, checks and exports.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/commands.hpp"
#include "apps/eigen_backend.hpp"
#include "apps/work_estimate.hpp"
#include "fe/dof.hpp"
#include "fe/error.hpp"
#include "io/input_error.hpp"
#include "io/model_reader.hpp"
#include "io/output_folder.hpp"
#include "io/reduced_export.hpp"
#include "reduction/frame_reduction.hpp"

namespace rigflex::app {
namespace {

struct ReduceArgs {
  std::string model;
  std::string interface_set;
  std::string method = "guyan";
  std::optional<int> modes;
  std::optional<double> cutoff_hz;
  std::string dofs = "all";            // six per node: what Simscape and most solvers take
  std::vector<std::string> node_dofs;  // "NODE:UX,UY,UZ,RZ"
  std::string support;  // empty: from the model
  std::optional<long> reference_node;
  double zeta = 0.02;
  std::vector<int> zeta_modes{1, 3};
  int check_modes = 10;
  std::string out;
  bool quiet = false;
  std::optional<double> max_memory_gib;
  BackendArgs backend;
};

reduction::FrameReductionOptions to_options(const ReduceArgs& a) {
  reduction::FrameReductionOptions o;
  o.interface_set = a.interface_set;
  o.method = *reduction::parse_reduction_method(a.method);
  o.retained = *reduction::parse_interface_dofs(a.dofs);
  for (const std::string& spec : a.node_dofs) {
    const auto colon = spec.find(':');
    const auto fail = [&](const std::string& why) {
      throw std::invalid_argument("--node-dofs '" + spec + "': " + why + " (as in 17:UX,UY,UZ,RZ)");
    };
    if (colon == std::string::npos) fail("expected NODE:DOFS");
    long node = 0;
    try {
      size_t used = 0;
      node = std::stol(spec.substr(0, colon), &used);
      if (used != colon) fail("the node is not an integer");
    } catch (const std::logic_error&) {
      fail("the node is not an integer");
    }
    fe::DofMask mask{};
    std::string rest = spec.substr(colon + 1) + ",";
    for (size_t start = 0, comma; (comma = rest.find(',', start)) != std::string::npos; start = comma + 1) {
      const std::string name = rest.substr(start, comma - start);
      const std::optional<int> local = fe::dof_index(name);
      if (!local) fail("'" + name + "' is not one of UX UY UZ RX RY RZ");
      mask[static_cast<size_t>(*local)] = true;
    }
    if (!o.node_dofs.emplace(node, mask).second) fail("node " + std::to_string(node) + " is given twice");
  }
  if (!a.support.empty()) o.support = *reduction::parse_frame_support(a.support);
  o.reference_node = a.reference_node;
  if (a.modes) o.modes = *a.modes;
  o.cutoff_hz = a.cutoff_hz;
  o.zeta = a.zeta;
  if (a.zeta_modes.size() != 2) throw std::invalid_argument("--zeta-modes: give two modes, as in 1,3");
  o.zeta_modes = {a.zeta_modes[0], a.zeta_modes[1]};
  o.check_modes = a.check_modes;
  if (!a.quiet) o.progress = [](const std::string& stage) { std::fprintf(stderr, "reduce: %s\n", stage.c_str()); };
  return o;
}

void print_summary(const reduction::ReducedFrame& r) {
  std::printf("model: %s, %ld free DOFs -> %ld interface DOFs + %d fixed-interface modes (%s, %s)\n", r.name.c_str(),
              r.full_free_dofs, static_cast<long>(r.interface_dof_count()), r.mode_count, to_string(r.method),
              to_string(r.support));
  const auto& d = r.damping;
  std::printf("Rayleigh damping: zeta %.4g at elastic modes %d (%.4f Hz) and %d (%.4f Hz): alpha = %.6g 1/s, "
              "beta = %.6g s\n",
              d.zeta[0], d.modes[0], d.omega[0] / (2 * M_PI), d.modes[1], d.omega[1] / (2 * M_PI), d.alpha, d.beta);
  const auto& c = r.checks;
  std::printf("%5s %14s %14s %10s %8s %8s   %s\n", "mode", "full [Hz]", "reduced [Hz]", "error %", "MAC", "zeta",
              "best match: reduced mode, MAC");
  for (const auto& f : c.frequencies) {
    const auto k = static_cast<Eigen::Index>(f.mode - 1);
    std::printf("%5d %14.6f %14.6f %10.4f %8.5f %8.5f   %4d %8.5f\n", f.mode, f.full_hz, f.reduced_hz, f.error_percent,
                f.mac, c.damping_ratios(k), f.matched_mode, f.matched_mac);
  }
  std::printf("MAC: full mode vs the expanded reduced mode(s) of the same index (a cluster if frequencies repeat)\n");
  std::printf("rigid-body modes: full %d, reduced %d", c.rigid_body_modes_full, c.rigid_body_modes_reduced);
  if (r.support == reduction::FrameSupport::free) std::printf(", residual ||K_r r|| %.2e", c.rigid_body_residual);
  std::printf("\n");
  const auto& ss = r.state_space;
  std::printf("state space: %ld states, %s coordinates", static_cast<long>(ss.A.rows()), to_string(ss.coordinates));
  if (ss.coordinates == reduction::StateCoordinates::modal)
    std::printf(" (z = T xi), the %d rigid-body modes exact: %d eigenvalues of A exactly zero", ss.rigid_body_modes,
                2 * ss.rigid_body_modes);
  std::printf("\n");
  const auto& mf = c.mass_full;
  const auto& mr = c.mass_reduced;
  std::printf("mass: full %.6g kg, CoG (%.6g, %.6g, %.6g) m\n", mf.mass, mf.cog.x(), mf.cog.y(), mf.cog.z());
  std::printf("      reduced %.6g kg, CoG (%.6g, %.6g, %.6g) m%s\n", mr.mass, mr.cog.x(), mr.cog.y(), mr.cog.z(),
              c.mass_comparable ? "" : "  (held frame: the reduced rigid-body mass is not the frame's)");
  if (c.mass_comparable) {
    std::printf("      inertia difference max %.3e of max |J|\n",
                (mr.inertia - mf.inertia).cwiseAbs().maxCoeff() / mf.inertia.cwiseAbs().maxCoeff());
  }
  std::printf("static interface flexibility, max |G_reduced - G_full| / max |G_full| = %.3e%s\n",
              c.static_flexibility_error, c.static_support.empty() ? "" : " (held isostatically at six interface DOFs)");
}

int run(const ReduceArgs& args) {
  // Under MPI every rank reduces (the eigen solves collectively, the
  // vectors gathered on every rank for the checks); rank 0 alone prints
  // and writes.
  const BackendRun backend(args.backend, true);
  const bool quiet = args.quiet || !backend.root();
  std::optional<io::OutputFolder> folder;
  if (backend.root()) folder.emplace(args.out, "reduce");
  const io::ModelFile m = io::read_model(args.model);
  const double limit = memory_limit_bytes(args.max_memory_gib);
  announce_assembly(args.model, m.model, limit, quiet, "reduce: ");
  if (!quiet && !backend.builtin()) std::fprintf(stderr, "reduce: eigen solver: %s\n", backend.describe().c_str());
  ReduceArgs effective = args;
  effective.quiet = quiet;
  reduction::FrameReductionOptions o = to_options(effective);
  o.max_factor_bytes = limit;
  o.eigen_backend = backend.backend();
  if (!quiet) {
    o.assembly_progress = assembly_progress("reduce: ");
    o.analyzed = [](const linalg::FactorStatistics& s) {
      std::fprintf(stderr, "reduce: %s\n", factor_line(s).c_str());
    };
  }
  reduction::ReducedFrame r;
  try {
    r = reduction::reduce_frame(m.model, o);
  } catch (const fe::ModelError& e) {
    throw io::InputError(args.model, 0, "--interface", e.what());
  } catch (const reduction::ReductionError& e) {
    if (!backend.root()) return 1;
    if (e.over_memory_limit) throw io::InputError(args.model, 0, "", memory_refusal(e.what()));
    std::fprintf(stderr, "rigflex: error: %s: %s\n", args.model.c_str(), e.what());
    if (!e.free_dofs.empty()) {
      std::fprintf(stderr, "free DOFs:\n");
      for (const auto& d : e.free_dofs) std::fprintf(stderr, "  %s\n", d.c_str());
      return 2;  // a mechanism: the model as given is wrong
    }
    return 1;
  }
  if (!backend.root()) return 0;
  r.name = m.name;
  print_summary(r);
  io::FileBatch batch;
  io::add_reduced_frame_files(batch, args.out, r);
  folder->commit(batch);
  std::printf("wrote %s/reduced.json, reduced.mat, K.mtx, M.mtx, C.mtx and ss_A..ss_D.mtx, ss_T.mtx\n",
              args.out.c_str());
  return 0;
}

}  // namespace

void add_reduce_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("reduce", "Reduce a frame onto its joint DOFs (Guyan or Craig-Bampton) and export");
  auto a = std::make_shared<ReduceArgs>();
  cmd->add_option("model", a->model, "model file (.yaml, or an Abaqus / CalculiX .inp deck)")->required();
  cmd->add_option("--interface", a->interface_set, "node set of the joint centres (the retained nodes)")->required();
  cmd->add_option("--method", a->method, "guyan | craig-bampton")
      ->check(CLI::IsMember({"guyan", "craig-bampton"}));
  auto* modes =
      cmd->add_option("--modes", a->modes, "Craig-Bampton: number of fixed-interface modes")->check(non_negative());
  cmd->add_option("--cutoff", a->cutoff_hz, "Craig-Bampton: keep the fixed-interface modes below this frequency [Hz]")
      ->excludes(modes);
  cmd->add_option("--dofs", a->dofs,
                  "retained DOFs per interface node: all (six, the default: what Simscape's Reduced Order Flexible "
                  "Solid takes) | translations")
      ->check(CLI::IsMember({"translations", "all"}));
  cmd->add_option("--node-dofs", a->node_dofs,
                  "NODE:UX,UY,UZ,RZ - the DOFs retained at that interface node instead of --dofs (repeatable; "
                  "rotations need --dofs all)");
  cmd->add_option("--support", a->support,
                  "grounded | free | reference-node (default: grounded if the model has supports, else free)")
      ->check(CLI::IsMember({"grounded", "free", "reference-node"}));
  cmd->add_option("--reference-node", a->reference_node, "node held for a reference-node reduction");
  cmd->add_option("--zeta", a->zeta, "Rayleigh damping ratio at the two --zeta-modes");
  cmd->add_option("--zeta-modes", a->zeta_modes, "two elastic modes of the full model, 1-based")->delimiter(',');
  cmd->add_option("--check-modes", a->check_modes, "elastic modes of the full model to compare")->check(positive());
  cmd->add_option("--out", a->out, "folder for reduced.json, reduced.mat and the .mtx files")->required();
  cmd->add_flag("--quiet", a->quiet, "no progress on stderr");
  cmd->add_option("--max-memory", a->max_memory_gib,
                  "GiB the assembly and each factorization may use (default: the machine's memory); a larger model "
                  "is refused before the work")
      ->check(positive());
  add_backend_options(*cmd, a->backend);
  cmd->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace rigflex::app
