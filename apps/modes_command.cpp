// rigflex modes MODEL.yaml [--count N] [--out DIR] [--block B]: natural frequencies,
// modal masses, effective mass fractions; modes.json and ParaView files.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/commands.hpp"
#include "apps/eigen_backend.hpp"
#include "apps/work_estimate.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/model_reader.hpp"
#include "io/output_folder.hpp"
#include "io/vtk_modes.hpp"
#include "reduction/ill_determined_modes.hpp"
#include "reduction/modal_analysis.hpp"
#include "reduction/zero_frequency_modes.hpp"
#include "report/modes_json.hpp"

namespace rigflex::app {
namespace {

struct ModesArgs {
  std::string model;
  int count = 10;
  std::string out;
  std::optional<double> shift_hz;
  int block = 0;
  bool quiet = false;
  bool allow_mechanism = false;
  std::optional<double> max_memory_gib;
  int subspace = 0;
  int max_restarts = linalg::EigenOptions{}.max_restarts;
  bool no_retry = false;
  BackendArgs backend;
};

// The elements that hold any of `nodes`, for naming the part a mechanism is in.
std::vector<std::string> elements_at(const fe::Model& model, const std::vector<fe::NodeId>& nodes) {
  std::vector<std::string> out;
  auto has = [&](fe::NodeId id) { return std::find(nodes.begin(), nodes.end(), id) != nodes.end(); };
  for (const fe::BeamElement& b : model.beams) {
    if (has(b.nodes[0]) || has(b.nodes[1])) out.push_back("beam " + b.id);
  }
  for (const fe::ShellElement& s : model.shells) {
    if (std::any_of(s.nodes.begin(), s.nodes.end(), has)) out.push_back("shell " + s.id);
  }
  for (const fe::SolidElement& s : model.solids) {
    if (std::any_of(s.nodes.begin(), s.nodes.end(), has)) out.push_back("solid " + s.id);
  }
  return out;
}

std::string describe(const reduction::ZeroFrequencyMode& z, const fe::Model& model) {
  std::string s = "mode " + std::to_string(z.mode + 1) + " moves ";
  for (size_t i = 0; i < z.largest.size(); ++i) s += (i ? ", " : "") + z.largest[i];
  if (z.moving > static_cast<Eigen::Index>(z.largest.size())) {
    s += " and " + std::to_string(z.moving - static_cast<Eigen::Index>(z.largest.size())) + " more DOFs";
  }
  // The elements its moving nodes belong to.
  const std::vector<std::string> parts = elements_at(model, z.nodes);
  if (!parts.empty()) {
    s += "; in ";
    for (size_t i = 0; i < std::min<size_t>(parts.size(), 6); ++i) s += (i ? ", " : "") + parts[i];
    if (parts.size() > 6) s += " and " + std::to_string(parts.size() - 6) + " more elements";
  }
  return s;
}

void report_not_converged(const std::string& path, const linalg::EigenResult& r) {
  std::fprintf(stderr, "rigflex: error: %s: the eigen solver stopped: %s\n", path.c_str(), r.message.c_str());
  std::fprintf(stderr,
               "  options: --subspace N (the basis), --block B, --max-restarts N, --shift-hz F; %d automatic "
               "retr%s run; nothing written\n",
               r.retries, r.retries == 1 ? "y" : "ies");
}

void print_table(const reduction::ModalAnalysis& a) {
  const auto& s = a.summary;
  std::printf("%5s %14s %14s %7s %7s %7s %7s %7s %7s %10s %10s\n", "mode", "f [Hz]", "modal mass", "TX", "TY", "TZ",
              "RX", "RY", "RZ", "residual", "backward");
  for (Eigen::Index k = 0; k < s.frequencies_hz.size(); ++k) {
    std::printf("%5ld %14.6f %14.6g", static_cast<long>(k + 1), s.frequencies_hz(k), s.modal_mass(k));
    for (int d = 0; d < 6; ++d) std::printf(" %7.4f", s.effective_mass_fraction(k, d));
    std::printf(" %10.2e %10.2e\n", a.result.residuals(k), a.result.backward_errors(k));
  }
  const Eigen::Index last = s.frequencies_hz.size() - 1;
  std::printf("%5s %14s %14s", "sum", "", "");
  for (int d = 0; d < 6; ++d) std::printf(" %7.4f", s.cumulative_fraction(last, d));
  std::printf("\n");
  std::printf(
      "effective mass fractions of the total in each rigid direction (rotations about the CoG); sum: over "
      "the modes listed\n");
  std::printf("residual ||Kx - lMx|| / ||Kx||; backward ||Kx - lMx|| / ((||K|| + |l| ||M||) ||x||)\n");
  std::printf("M-orthonormality error max|X'MX - I| = %.2e\n", a.result.orthogonality_error);
}

int run(const ModesArgs& args) {
  // Under MPI every rank reads, assembles and takes its part in the solve;
  // rank 0 alone prints and writes.
  const BackendRun backend(args.backend, false);
  const bool quiet = args.quiet || !backend.root();
  std::optional<io::OutputFolder> folder;
  if (!args.out.empty() && backend.root()) folder.emplace(args.out, "modes");
  const io::ModelFile m = io::read_model(args.model);
  const double limit = memory_limit_bytes(args.max_memory_gib);
  announce_assembly(args.model, m.model, limit, quiet);
  if (!quiet && !backend.builtin()) std::fprintf(stderr, "eigen solver: %s\n", backend.describe().c_str());
  linalg::EigenOptions opt;
  opt.max_factor_bytes = limit;
  if (!quiet) {
    opt.analyzed = [](const linalg::FactorStatistics& s) { std::fprintf(stderr, "%s\n", factor_line(s).c_str()); };
  }
  opt.count = args.count;
  opt.block_size = args.block;
  opt.subspace = args.subspace;
  opt.max_restarts = args.max_restarts;
  opt.automatic_retry = !args.no_retry;
  if (args.shift_hz) opt.shift = -std::pow(2 * M_PI * *args.shift_hz, 2);
  const char* solver = backend.builtin() ? "Lanczos" : "Krylov-Schur";
  if (!quiet)
    opt.progress = [solver](const linalg::EigenProgress& p) {
      std::fprintf(stderr, "\r%s: restart %d, %d converged", solver, p.restart, p.converged);
      std::fflush(stderr);
    };
  fe::AssemblyOptions assembly;
  if (!quiet) assembly.progress = assembly_progress();
  const reduction::ModalAnalysis a = reduction::run_modal_analysis(m.model, opt, assembly, backend.backend());
  if (!backend.root()) return 0;
  if (!quiet) {
    std::fprintf(stderr, "\nfactorization %.2f s, %s %.2f s\n", a.result.factor_seconds, solver,
                 a.result.iteration_seconds);
  }
  if (a.result.over_memory_limit) {
    throw io::InputError(args.model, 0, "", memory_refusal(a.result.message));
  }
  std::printf("model: %s, %ld free DOFs, mass %.6g kg\n", m.name.c_str(), static_cast<long>(a.system.dofs.free_count()),
              a.mass.mass);
  if (!a.mechanism.empty()) {
    std::fprintf(stderr, "rigflex: error: %s: the model is a mechanism; K - sigma M is singular. Free DOFs:\n",
                 args.model.c_str());
    for (const auto& d : a.mechanism) std::fprintf(stderr, "  %s\n", d.c_str());
    std::fprintf(stderr, "add supports, springs or mass to these DOFs\n");
    return 2;
  }
  if (!a.result.converged) {
    report_not_converged(args.model, a.result);
    return 1;
  }
  if (a.result.retries > 0) {
    std::printf("note: the eigen solver converged on an automatic retry with a larger basis; the first attempt: %s\n",
                a.result.first_attempt.c_str());
  }
  print_table(a);
  for (const auto& w : reduction::rotation_only_modes(a.summary, a.mass.mass)) {
    if (w.drilling) {
      std::fprintf(stderr, "rigflex: warning: %s\n", reduction::describe(w, a.summary).c_str());
    } else {
      std::printf("note: %s\n", reduction::describe(w, a.summary).c_str());
    }
  }
  const std::vector<reduction::ZeroFrequencyMode> zero = reduction::zero_frequency_modes(m.model, a);
  const bool supported = reduction::is_supported(m.model);
  if (!zero.empty() && supported && !args.allow_mechanism) {
    std::fprintf(stderr,
                 "rigflex: error: %s: the model is supported but %zu mode(s) have zero frequency: a mechanism, "
                 "a part that moves without straining anything:\n",
                 args.model.c_str(), zero.size());
    for (const auto& z : zero) {
      std::fprintf(stderr, "  %s\n", describe(z, m.model).c_str());
    }
    std::fprintf(stderr,
                 "add supports, connections or stiffness to these DOFs, or pass --allow-mechanism to keep "
                 "them; nothing written\n");
    return 2;
  }
  if (!zero.empty()) {
    std::printf("modes 1-%zu have zero frequency: %s\n", zero.size(),
                supported ? "a mechanism, kept (--allow-mechanism)" : "rigid-body motions of the free model");
  }
  const std::vector<reduction::IllDeterminedMode> vague = reduction::ill_determined_modes(a, zero);
  if (!vague.empty()) std::fprintf(stderr, "rigflex: warning: %s\n", reduction::describe(vague, a).c_str());
  if (folder) {
    const std::filesystem::path dir(args.out);
    io::FileBatch batch;
    nlohmann::json j = report::modes_json(m.name, a);
    j["supported"] = supported;
    if (!backend.builtin()) j["solver"]["method"] = backend.describe();
    j["zero_frequency_modes"] = nlohmann::json::array();
    for (const auto& z : zero) j["zero_frequency_modes"].push_back(z.mode + 1);
    j["ill_determined_modes"] = nlohmann::json::array();
    for (const auto& v : vague) {
      j["ill_determined_modes"].push_back({{"mode", v.mode + 1}, {"relative_error", v.relative_error}});
    }
    batch.add_text(dir / "modes.json", j.dump(2) + "\n");
    io::add_mode_shape_files(batch, dir, m.model, a.system.dofs, a.summary.frequencies_hz, a.result.vectors);
    folder->commit(batch);
    std::printf("wrote %s/modes.json, modes.pvd and %ld mode_NNN.vtu\n", args.out.c_str(),
                static_cast<long>(a.result.vectors.cols()));
  }
  return 0;
}

}  // namespace

void add_modes_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("modes", "Natural frequencies and mode shapes of a model");
  auto args = std::make_shared<ModesArgs>();
  cmd->add_option("model", args->model, "model file (.yaml, or an Abaqus / CalculiX .inp deck)")->required();
  cmd->add_option("--count", args->count, "number of modes (lowest first)")->check(positive());
  cmd->add_option("--out", args->out, "folder for modes.json, modes.pvd and mode_NNN.vtu");
  cmd->add_option("--shift-hz", args->shift_hz, "spectral shift as a frequency: sigma = -(2 pi f)^2");
  cmd->add_option(
         "--block", args->block,
         "Lanczos block size; 0 (default): chosen from the size of the factor and basis, see docs/eigen-solver.md")
      ->check(non_negative());
  cmd->add_option("--subspace", args->subspace,
                  "Lanczos basis size; 0 (default): max(2 count, count + 20, count + 2 block)")
      ->check(non_negative());
  cmd->add_option("--max-restarts", args->max_restarts, "Lanczos thick restarts before it gives up (default 200)")
      ->check(non_negative());
  cmd->add_flag("--no-retry", args->no_retry,
                "no automatic retry with a larger basis when Lanczos stalls (see docs/eigen-solver.md)");
  cmd->add_flag("--quiet", args->quiet, "no progress on stderr");
  cmd->add_option("--max-memory", args->max_memory_gib,
                  "GiB the assembly and the factor may use (default: the machine's memory); a larger model is "
                  "refused before the work")
      ->check(positive());
  cmd->add_flag("--allow-mechanism", args->allow_mechanism,
                "keep zero-frequency modes of a supported model (otherwise an error, exit 2)");
  add_backend_options(*cmd, args->backend);
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace rigflex::app
