// Benchmark: the 20 lowest modes of a clamped steel plate of MITC4 shells
// (1 m x 1 m x 10 mm, all four edges clamped, n x n elements), at about
// 10k, 100k, 500k and 1M DOFs, against
//   (a) the floor: one CHOLMOD factorization of K - sigma M at the same
//       shift plus the solves the Lanczos needed (EigenResult::
//       operator_applications right-hand sides: in blocks of the Lanczos
//       block size, and the final purification of the converged vectors
//       in one solve), timed separately on a fresh SparseCholesky;
//   (b) CalculiX *FREQUENCY on the same mesh (S4 shells, see
//       verification/calculix.hpp), run as a child process;
//   (c) SciPy eigsh (ARPACK shift-invert with SuperLU, Debian
//       python3-scipy) on the same K and M (Matrix Market), same shift,
//       run as a child process (bench/scipy_eigsh.py);
//   (d) SLEPc's Krylov-Schur with shift-and-invert (linalg/slepc_eigen.hpp)
//       on the same K and M, same shift and tolerance, through
//       bench/slepc_eigs under mpiexec: with CHOLMOD on one rank (the
//       factorization rigflex uses) and with MUMPS on each of --slepc-ranks
//       (built with -DRIGFLEX_SLEPC=ON; one table row per configuration).
// Targets (issue): at 100k and 1M DOFs eigen time within 1.5x of the floor,
// at least 5x faster than CalculiX and SciPy, peak memory within 1.5x of
// the factor's size.
//
// Usage:
//   bench_plate_modes [--sizes 10k,100k,500k,1M] [--modes 20] [--block 4] [--repeat 1]
//                     [--skip-ccx] [--skip-scipy] [--max-peer-dofs 150000]
//                     [--ccx-threads 1] [--scipy-timeout SECONDS] [--workdir /tmp/rigflex-bench-plate]
//                     [--scipy-script bench/scipy_eigsh.py] [--keep]
//                     [--skip-slepc] [--slepc-ranks 1,2] [--max-slepc-dofs 2M] [--model plate|ladder|girder|lattice]
// Prints a markdown table on stdout, progress on stderr.
//
// Measurement notes:
//   * rigflex times: "assembly" = fe::assemble (meshing not included);
//     "eigen" = wall time of linalg::solve_lanczos, which includes its own
//     factorization ("factor" = EigenResult::factor_seconds), the Lanczos
//     iteration, Rayleigh-Ritz and the residual check.
//   * "peak RSS" = VmHWM of this process from meshing to the end of
//     solve_lanczos (reset per size through /proc/self/clear_refs): model,
//     assembly (triplets), K, M, factor, Lanczos basis. "eigen peak" =
//     VmHWM during solve_lanczos (reset before it) minus VmRSS before it
//     (taken after malloc_trim, so that memory freed by assembly but kept
//     by the allocator is not counted as free room for the solver): the
//     eigen solver's own memory, the quantity the issue's "peak memory
//     within 1.5x of the factor's size" is about. The floor, the exports
//     and the peers run after these are read. Peers' peak RSS: wait4.
//   * ccx ratio: ccx wall time / (rigflex assembly + eigen): ccx's time
//     includes its input parsing, shell expansion and assembly. SciPy ratio:
//     eigsh wall time / rigflex eigen time (reading the .mtx files excluded).
#include <fcntl.h>
#include <malloc.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_cli.hpp"
#include "bench/bench_models.hpp"
#include "bench/plate_model.hpp"
#include "fe/assembly.hpp"
#include "fe/meshers.hpp"
#include "linalg/eigen_solver.hpp"
#include "linalg/sparse_cholesky.hpp"
#include "verification/calculix.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace rigflex;
using bench::clamped_plate;
using bench::divisions_for;
using bench::loadavg;
using bench::reset_peak_rss;
using bench::status_kb;
using bench::clock_type;
using bench::seconds_since;

struct Options {
  std::vector<long> sizes{10000, 100000};
  int modes = 20;
  // Lanczos block size; 0: the solver's automatic choice (4 on this plate
  // from about 40k DOFs, where one 4-column solve costs about 1.8 single
  // ones and the block iteration wins; 1 below). Each row reports the size
  // used.
  int block = 0;
  int repeat = 1;  // rigflex eigen and floor timings: best of `repeat` (the machine is shared)
  bool ccx = true, scipy = true, keep = false;
  long max_peer_dofs = 150000;
  double scipy_timeout = 0;  // seconds, 0 = none; SciPy at 1M DOFs may run for an hour
  // SPOOLES' multithreaded solve (CCX_NPROC_EQUATION_SOLVER=2) made ccx's
  // *FREQUENCY 4x slower in CPU time on the 10k plate (16 s vs 3.6 s): the
  // peer runs in its fastest configuration, one thread.
  int ccx_threads = 1;
  fs::path workdir = "/tmp/rigflex-bench-plate";
  fs::path scipy_script = fs::path(__FILE__).parent_path() / "scipy_eigsh.py";
#ifdef RIGFLEX_SLEPC_EIGS
  bool slepc = true;
#else
  bool slepc = false;
#endif
  std::vector<long> slepc_ranks{1, 2};
  long max_slepc_dofs = 2000000;
  // plate (the clamped plate above) or another kind of bench_models.hpp:
  // ladder (beam ladder), girder (shell box girder), lattice (3D beam
  // lattice), quad8 (8-node plate).
  std::string model = "plate";
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] { return bench::option_value(argc, argv, i); };
    if (a == "--sizes") {
      o.sizes = bench::parse_sizes(value());
    } else if (a == "--modes") o.modes = std::stoi(value());
    else if (a == "--block") o.block = std::stoi(value());
    else if (a == "--repeat") o.repeat = std::max(1, std::stoi(value()));
    else if (a == "--skip-ccx") o.ccx = false;
    else if (a == "--skip-scipy") o.scipy = false;
    else if (a == "--max-peer-dofs") o.max_peer_dofs = bench::parse_size(value());
    else if (a == "--ccx-threads") o.ccx_threads = std::stoi(value());
    else if (a == "--scipy-timeout") o.scipy_timeout = std::stod(value());
    else if (a == "--workdir") o.workdir = value();
    else if (a == "--scipy-script") o.scipy_script = value();
    else if (a == "--keep") o.keep = true;
    else if (a == "--skip-slepc")
      o.slepc = false;
    else if (a == "--model")
      o.model = value();
    else if (a == "--slepc-ranks")
      o.slepc_ranks = bench::parse_sizes(value());
    else if (a == "--max-slepc-dofs")
      o.max_slepc_dofs = bench::parse_size(value());
    else throw std::invalid_argument("unknown option " + a + " (see the head of bench_plate_modes.cpp)");
  }
  return o;
}

// ---- memory -------------------------------------------------------------

// Hands memory freed by assembly back to the system, so that it does not
// count as room for the solver.
void release_freed_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

// ---- Matrix Market (lower triangle of a symmetric matrix) ------------------

void write_mtx(const fe::SpMat& A, const fs::path& file) {
  long entries = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (fe::SpMat::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) ++entries;
  FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + file.string());
  std::fprintf(f, "%%%%MatrixMarket matrix coordinate real symmetric\n%ld %ld %ld\n", (long)A.rows(),
               (long)A.cols(), entries);
  std::vector<char> buf(1 << 20);
  size_t used = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (fe::SpMat::InnerIterator it(A, j); it; ++it) {
      if (it.row() < j) continue;
      if (used + 64 > buf.size()) {
        std::fwrite(buf.data(), 1, used, f);
        used = 0;
      }
      char* p = buf.data() + used;
      char* end = buf.data() + buf.size();
      p = std::to_chars(p, end, static_cast<long>(it.row() + 1)).ptr;
      *p++ = ' ';
      p = std::to_chars(p, end, static_cast<long>(j + 1)).ptr;
      *p++ = ' ';
      p = std::to_chars(p, end, it.value()).ptr;
      *p++ = '\n';
      used = static_cast<size_t>(p - buf.data());
    }
  std::fwrite(buf.data(), 1, used, f);
  if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + file.string());
}

// ---- child processes -----------------------------------------------------------

struct ChildResult {
  int status = -1;
  double seconds = 0;
  long max_rss_kb = 0;
  bool timed_out = false;
  std::string output;
};

// Runs argv with stdout to out_file; kills it after `timeout` seconds (0:
// no limit) and reports that.
ChildResult run_child(const std::vector<std::string>& argv, const fs::path& out_file, double timeout = 0) {
  std::vector<std::string> store = argv;
  std::vector<char*> args;
  for (auto& s : store) args.push_back(s.data());
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const fs::path err_file = out_file.string() + ".err";
  posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ChildResult r;
  pid_t pid = 0;
  const auto t0 = clock_type::now();
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  int status = 0;
  struct rusage usage {};
  while (true) {
    const pid_t done = ::wait4(pid, &status, timeout > 0 ? WNOHANG : 0, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) throw std::runtime_error("wait4 failed");
    if (done == 0) {
      if (!r.timed_out && seconds_since(t0) > timeout) {
        ::kill(pid, SIGKILL);
        r.timed_out = true;
      }
      ::usleep(100000);
    }
  }
  r.seconds = seconds_since(t0);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  r.max_rss_kb = usage.ru_maxrss;
  std::ifstream in(out_file);
  r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (r.status != 0) {
    std::ifstream err(err_file);
    r.output += std::string(std::istreambuf_iterator<char>(err), std::istreambuf_iterator<char>());
  }
  return r;
}

// Minimal reader for the flat JSON line of scipy_eigsh.py.
double json_number(const std::string& text, const std::string& key) {
  const auto at = text.find("\"" + key + "\":");
  if (at == std::string::npos) throw std::runtime_error("scipy output lacks " + key + ":\n" + text);
  return std::stod(text.substr(at + key.size() + 3));
}
std::vector<double> json_numbers(const std::string& text, const std::string& key) {
  const auto at = text.find("\"" + key + "\": [");
  if (at == std::string::npos) throw std::runtime_error("scipy output lacks " + key);
  const auto end = text.find(']', at);
  std::istringstream in(text.substr(at + key.size() + 5, end - at - key.size() - 5));
  std::vector<double> v;
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  return v;
}

double max_rel_diff(const std::vector<double>& a, const Eigen::VectorXd& ref) {
  double d = 0;
  for (size_t i = 0; i < a.size() && static_cast<Eigen::Index>(i) < ref.size(); ++i)
    d = std::max(d, std::abs(a[i] - ref[static_cast<Eigen::Index>(i)]) / ref[static_cast<Eigen::Index>(i)]);
  return d;
}

// ---- one size -------------------------------------------------------------------

struct Row {
  long dofs = 0;
  int n = 0;
  double mesh = 0, assembly = 0, factor = 0, eigen = 0, floor_factor = 0, floor_solves = 0;
  double peak_mb = 0, base_mb = 0, factor_mb = 0, max_residual = 0, orthogonality = 0;
  double assembly_peak_mb = 0, eigen_base_mb = 0, eigen_peak_mb = 0;  // VmHWM per phase, VmRSS before eigen
  std::string load;
  long applications = 0;
  int block = 0;  // Lanczos block size used
  int restarts = 0, converged = 0;
  bool peak_reset = false;
  std::optional<double> ccx_s, ccx_rss_mb, ccx_diff, scipy_s, scipy_rss_mb, scipy_diff, scipy_residual;
  long ccx_equations = 0;
  std::string ccx_note, scipy_note;
  struct Slepc {
    std::string solver;
    long ranks = 1;
    double setup = 0, solve = 0, eigen = 0, rss_max_rank = 0, rss_all = 0, diff = 0, residual = 0;
    long solves = 0;
    std::string note;  // set when it did not run to the end
  };
  std::vector<Slepc> slepc;
  double floor() const { return floor_factor + floor_solves; }
};

Row run_size(long target, const Options& o) {
  Row row;
  const bool plate = o.model == "plate";
  row.n = plate ? divisions_for(target) : 0;
  if (plate)
    std::cerr << "== " << target << " DOFs: " << row.n << " x " << row.n << " MITC4 elements\n";
  else
    std::cerr << "== " << o.model << " of about " << target << " DOFs\n";
  row.peak_reset = reset_peak_rss();
  row.base_mb = status_kb("VmRSS:") / 1024.0;
  row.load = loadavg();
  auto t0 = clock_type::now();
  std::string kind;
  fe::Model model = plate ? clamped_plate(row.n) : bench::model_of(o.model + ":" + std::to_string(target), kind);
  row.mesh = seconds_since(t0);
  t0 = clock_type::now();
  fe::AssembledSystem sys = fe::assemble(model);
  row.assembly = seconds_since(t0);
  row.dofs = static_cast<long>(sys.K.rows());
  row.assembly_peak_mb = status_kb("VmHWM:") / 1024.0;
  // Hand what assembly freed back to the system first: otherwise the solver
  // could reuse that resident garbage without its RSS growing, and the
  // eigen peak would under-report its memory.
  release_freed_memory();
  reset_peak_rss();
  row.eigen_base_mb = status_kb("VmRSS:") / 1024.0;
  std::cerr << "   assembled " << row.dofs << " DOFs in " << row.assembly << " s\n";

  linalg::EigenOptions eo;
  eo.count = o.modes;
  eo.block_size = o.block;
  eo.method = linalg::EigenMethod::lanczos;
  t0 = clock_type::now();
  const linalg::EigenResult r = linalg::solve_lanczos(sys.K, sys.M, eo);
  row.eigen = seconds_since(t0);
  row.eigen_peak_mb = status_kb("VmHWM:") / 1024.0;
  row.peak_mb = std::max(row.assembly_peak_mb, row.eigen_peak_mb);
  row.factor = r.factor_seconds;
  row.applications = r.operator_applications;
  row.block = r.block_size;
  row.restarts = r.restarts;
  row.converged = r.converged_count;
  row.max_residual = r.residuals.size() ? r.residuals.maxCoeff() : NAN;
  row.orthogonality = r.orthogonality_error;
  if (!r.converged) std::cerr << "   WARNING: Lanczos not converged: " << r.message << "\n";
  const Eigen::VectorXd f = r.frequencies_hz();
  std::cerr << "   eigen " << row.eigen << " s (factor " << r.factor_seconds << " s), " << r.operator_applications
            << " operator applications, f1 = " << f[0] << " Hz, max residual " << row.max_residual << "\n";

  // (a) floor: same shift, the same solves. With --repeat, the Lanczos and
  // the floor alternate and each keeps its best time.
  for (int rep = 0; rep < o.repeat; ++rep) {
    if (rep > 0) {
      t0 = clock_type::now();
      const linalg::EigenResult again = linalg::solve_lanczos(sys.K, sys.M, eo);
      const double t = seconds_since(t0);
      if (t < row.eigen) row.eigen = t, row.factor = again.factor_seconds;
    }
    linalg::SparseCholesky floor_factor;
    t0 = clock_type::now();
    const linalg::FactorStatus st = floor_factor.factorize_shifted(sys.K, sys.M, r.shift);
    const double factor_s = seconds_since(t0);
    if (!st.ok) throw std::runtime_error("floor factorization failed: " + st.message);
    row.factor_mb = floor_factor.statistics().factor_bytes / (1024.0 * 1024.0);
    // The solves the Lanczos made: its applications in blocks of the block
    // size, then the purification of the converged vectors, one solve with
    // that many columns.
    const long b = std::max(1, r.block_size);
    const long purified = r.converged_count;
    const long iteration = r.operator_applications - purified;
    std::vector<long> widths;
    for (long done = 0; done < iteration; done += b) widths.push_back(std::min(b, iteration - done));
    if (purified > 0) widths.push_back(purified);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(row.dofs, std::max(b, purified));
    double checksum = 0;
    t0 = clock_type::now();
    for (const long cols : widths) {
      const Eigen::MatrixXd X = floor_factor.solve(Eigen::MatrixXd(B.leftCols(cols)));
      checksum += X(0, 0);
    }
    const double solves_s = seconds_since(t0);
    if (!std::isfinite(checksum)) std::cerr << "   (non-finite floor checksum)\n";
    if (rep == 0 || factor_s + solves_s < row.floor()) row.floor_factor = factor_s, row.floor_solves = solves_s;
    std::cerr << "   floor " << factor_s + solves_s << " s (factor " << factor_s << " s, solves " << solves_s
              << " s), factor " << row.factor_mb << " MB\n";
  }
  if (o.repeat > 1) std::cerr << "   best of " << o.repeat << ": eigen " << row.eigen << " s, floor " << row.floor() << " s\n";

  const bool peers = row.dofs <= o.max_peer_dofs;
  const fs::path dir = o.workdir / (o.model + std::to_string(row.dofs));
  fs::create_directories(dir);

  char sigma[64], tol[32];
  std::snprintf(sigma, sizeof sigma, "%.17g", r.shift);
  std::snprintf(tol, sizeof tol, "%.3g", eo.tolerance);
  bool written = false;
  const auto write_matrices = [&] {
    if (!written) write_mtx(sys.K, dir / "K.mtx"), write_mtx(sys.M, dir / "M.mtx");
    written = true;
  };

#ifdef RIGFLEX_SLEPC_EIGS
  // (d) SLEPc on the same matrices: CHOLMOD on one rank, MUMPS on each rank count.
  if (o.slepc && row.dofs <= o.max_slepc_dofs) {
    write_matrices();
    std::vector<std::pair<std::string, long>> runs{{"cholmod", 1}};
    for (long ranks : o.slepc_ranks) runs.emplace_back("mumps", ranks);
    for (const auto& [solver, ranks] : runs) {
      Row::Slepc s;
      s.solver = solver;
      s.ranks = ranks;
      std::cerr << "   slepc " << solver << " on " << ranks << " rank(s) ...\n";
      const ChildResult c =
          run_child({RIGFLEX_MPIEXEC, "-n", std::to_string(ranks), RIGFLEX_SLEPC_EIGS, (dir / "K.mtx").string(),
                     (dir / "M.mtx").string(), "--count", std::to_string(o.modes), "--shift", sigma, "--tol", tol,
                     "--direct-solver", solver},
                    dir / ("slepc_" + solver + "_" + std::to_string(ranks) + ".json"));
      if (c.status != 0) {
        s.note = "failed (status " + std::to_string(c.status) + ")";
        std::cerr << c.output << "\n";
      } else {
        s.setup = json_number(c.output, "setup_seconds");
        s.solve = json_number(c.output, "solve_seconds");
        s.eigen = json_number(c.output, "eigen_seconds");
        s.solves = static_cast<long>(json_number(c.output, "solves"));
        s.rss_max_rank = json_number(c.output, "rss_mb_max_rank");
        s.rss_all = json_number(c.output, "rss_mb_all_ranks");
        s.residual = json_number(c.output, "max_residual");
        s.diff = max_rel_diff(json_numbers(c.output, "frequencies_hz"), f);
        std::cerr << "   slepc " << solver << " x" << ranks << ": " << s.eigen << " s (factor " << s.setup
                  << " s), max df/f " << s.diff << "\n";
      }
      row.slepc.push_back(s);
    }
  }
#endif

  // (c) SciPy on the same matrices.
  if (o.scipy && peers) {
    write_matrices();
    std::cerr << "   scipy eigsh ...\n";
    const ChildResult c =
        run_child({"/usr/bin/python3", o.scipy_script.string(), (dir / "K.mtx").string(), (dir / "M.mtx").string(),
                   std::to_string(o.modes), sigma, tol},
                  dir / "scipy.json", o.scipy_timeout);
    if (c.timed_out) {
      char note[64];
      std::snprintf(note, sizeof note, "> %.0f s (stopped)", o.scipy_timeout);
      row.scipy_note = note;
    } else if (c.status != 0) {
      row.scipy_note = "failed (status " + std::to_string(c.status) + ")";
      std::cerr << c.output << "\n";
    } else {
      row.scipy_s = json_number(c.output, "eigsh_seconds");
      row.scipy_rss_mb = c.max_rss_kb / 1024.0;
      row.scipy_residual = json_number(c.output, "max_residual");
      row.scipy_diff = max_rel_diff(json_numbers(c.output, "frequencies_hz"), f);
      std::cerr << "   scipy eigsh " << *row.scipy_s << " s (read " << json_number(c.output, "read_seconds")
                << " s), peak RSS " << *row.scipy_rss_mb << " MB\n";
    }
  } else if (o.scipy) {
    row.scipy_note = "skipped (> max-peer-dofs)";
  }

  // (b) CalculiX on the same mesh.
  if (o.ccx && peers) {
    if (!verification::calculix_available()) {
      row.ccx_note = "ccx not on PATH";
    } else {
      std::cerr << "   ccx ...\n";
      verification::CalculixRunOptions run;
      run.threads = o.ccx_threads;
      try {
        const verification::CalculixFrequencies c = verification::run_calculix_frequencies(model, o.modes, dir / "ccx", run);
        row.ccx_s = c.wall_seconds;
        row.ccx_rss_mb = c.max_rss_kb / 1024.0;
        row.ccx_equations = c.equations;
        row.ccx_diff = max_rel_diff(c.frequencies_hz, f);
        std::cerr << "   ccx " << c.wall_seconds << " s, " << c.equations << " equations, peak RSS "
                  << *row.ccx_rss_mb << " MB\n";
      } catch (const std::exception& e) {
        row.ccx_note = "failed";
        std::cerr << e.what() << "\n";
      }
    }
  } else if (o.ccx) {
    row.ccx_note = "skipped (> max-peer-dofs)";
  }
  if (!o.keep) fs::remove_all(dir);
  return row;
}

std::string fmt(double v, int digits = 2) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}
std::string fmt_e(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.1e", v);
  return b;
}

void print_tables(const std::vector<Row>& rows, const Options& o, std::ostream& out) {
  const char* threads = std::getenv("OPENBLAS_NUM_THREADS");
  out << "\n### "
      << (o.model == "plate" ? std::string("Clamped 1 m x 1 m x 10 mm steel plate, MITC4")
                             : "Model " + o.model + " (bench/bench_models.hpp)")
      << ", " << o.modes << " modes, block size " << (o.block > 0 ? std::to_string(o.block) : std::string("automatic"))
      << ", rigflex times best of " << o.repeat << ", OPENBLAS_NUM_THREADS " << (threads ? threads : "unset") << "\n\n";
  out << "| DOFs | n x n | block | assembly s | factor s | eigen s | floor s | eigen/floor | ccx s | ccx/rigflex | "
               "scipy s | scipy/rigflex | peak RSS MB | eigen peak MB | factor MB | eigen peak/factor | max residual |\n";
  out << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    const double total = r.assembly + r.eigen;
    out << "| " << r.dofs << " | " << (r.n ? std::to_string(r.n) + "x" + std::to_string(r.n) : o.model) << " | "
        << r.block << " | " << fmt(r.assembly) << " | " << fmt(r.factor) << " | " << fmt(r.eigen) << " | "
        << fmt(r.floor()) << " | " << fmt(r.eigen / r.floor()) << " | "
        << (r.ccx_s              ? fmt(*r.ccx_s, 1)
            : r.ccx_note.empty() ? "-"
                                 : r.ccx_note)
        << " | " << (r.ccx_s ? fmt(*r.ccx_s / total, 1) : "-") << " | "
        << (r.scipy_s              ? fmt(*r.scipy_s, 1)
            : r.scipy_note.empty() ? "-"
                                   : r.scipy_note)
        << " | " << (r.scipy_s ? fmt(*r.scipy_s / r.eigen, 1) : "-") << " | " << fmt(r.peak_mb, 0)
        << (r.peak_reset ? "" : " (not reset)") << " | " << fmt(r.eigen_peak_mb - r.eigen_base_mb, 0) << " | "
        << fmt(r.factor_mb, 0) << " | " << fmt((r.eigen_peak_mb - r.eigen_base_mb) / r.factor_mb) << " | "
        << fmt_e(r.max_residual) << " |\n";
  }
  out << "\n| DOFs | base RSS MB | assembly peak MB | RSS before eigen MB | mesh s | floor factor s | floor solves s | op. applications | restarts | converged | "
               "M-orth. error | ccx equations | ccx peak RSS MB | ccx max df/f | scipy peak RSS MB | scipy max df/f "
               "| scipy max residual | load avg |\n";
  out << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    out << "| " << r.dofs << " | " << fmt(r.base_mb, 0) << " | " << fmt(r.assembly_peak_mb, 0) << " | "
        << fmt(r.eigen_base_mb, 0) << " | " << fmt(r.mesh) << " | " << fmt(r.floor_factor) << " | " << fmt(r.floor_solves)
              << " | " << r.applications << " | " << r.restarts << " | " << r.converged << "/" << o.modes << " | "
              << fmt_e(r.orthogonality) << " | " << (r.ccx_equations ? std::to_string(r.ccx_equations) : "-") << " | "
              << (r.ccx_rss_mb ? fmt(*r.ccx_rss_mb, 0) : "-") << " | " << (r.ccx_diff ? fmt_e(*r.ccx_diff) : "-")
              << " | " << (r.scipy_rss_mb ? fmt(*r.scipy_rss_mb, 0) : "-") << " | "
              << (r.scipy_diff ? fmt_e(*r.scipy_diff) : "-") << " | "
              << (r.scipy_residual ? fmt_e(*r.scipy_residual) : "-") << " | " << r.load << " |\n";
  }
  bool any_slepc = false;
  for (const Row& r : rows) any_slepc = any_slepc || !r.slepc.empty();
  if (any_slepc) {
    out << "\n| DOFs | SLEPc Krylov-Schur with | ranks | factor s | iteration s | eigen s | solves | rigflex eigen s | "
           "SLEPc / rigflex | rigflex floor s | max df/f | max residual | peak RSS MB, largest rank | all ranks |\n";
    out << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      for (const Row::Slepc& s : r.slepc) {
        out << "| " << r.dofs << " | " << s.solver << " | " << s.ranks << " | ";
        if (!s.note.empty()) {
          out << s.note << " | | | | " << fmt(r.eigen) << " | | " << fmt(r.floor()) << " | | | | |\n";
          continue;
        }
        out << fmt(s.setup) << " | " << fmt(s.solve) << " | " << fmt(s.eigen) << " | " << s.solves << " | "
            << fmt(r.eigen) << " | " << fmt(s.eigen / r.eigen) << " | " << fmt(r.floor()) << " | " << fmt_e(s.diff)
            << " | " << fmt_e(s.residual) << " | " << fmt(s.rss_max_rank, 0) << " | " << fmt(s.rss_all, 0) << " |\n";
      }
    out << "\nSLEPc: bench/slepc_eigs under mpiexec on the K.mtx and M.mtx above, rigflex's shift and tolerance, "
           "the same number of modes; factor = EPSSetUp (the factorization of K - sigma M), iteration = EPSSolve, "
           "eigen = both (reading the files excluded); solves = right-hand sides solved. SLEPc / rigflex = SLEPc's "
           "eigen over rigflex's eigen (> 1: rigflex faster). Peak RSS = VmHWM of each rank, which holds the whole "
           "K and M as read (as the command line's ranks each hold the assembled model).\n";
  }
  out << "\nfloor = factorize_shifted(K, M, sigma) + the solves of the Lanczos on a fresh factor: (operator "
         "applications - converged) / block solves of `block` column(s), one of `converged` columns (the "
         "purification). eigen = wall of solve_lanczos "
         "(its own factorization included). "
         "ccx/rigflex = ccx wall / (assembly + eigen); ccx ran with "
      << o.ccx_threads
      << " thread(s) on its expanded C3D8I model. scipy/rigflex = eigsh wall / eigen (SuperLU + ARPACK, tol = "
         "rigflex's tolerance, reading the .mtx excluded). peak RSS = VmHWM of the process from meshing to the end "
         "of solve_lanczos (base RSS = before meshing: libraries, warm-up leftovers). eigen peak = VmHWM during "
         "solve_lanczos minus VmRSS before it (K, M and the model already resident; taken after malloc_trim, so "
         "that memory assembly freed does not count as room for the solver): the solver's own memory (factor, "
         "K - sigma M while factorizing, Lanczos basis). Peers' RSS from wait4 (scipy's includes mmread). df/f = max "
         "relative difference of the "
      << o.modes
      << " frequencies to rigflex's. load avg (1, 5, 15 min) when the size started: the machine is shared, "
         "timings under load > 2 are inflated.\n";
}

// Factor and solve a small plate once, so that the first measured size does
// not pay for first-touch allocation and BLAS thread start-up.
void warm_up() {
  const fe::AssembledSystem sys = fe::assemble(clamped_plate(24));
  linalg::SparseCholesky f;
  f.factorize_shifted(sys.K, sys.M, -1.0);
  for (int i = 0; i < 10; ++i) f.solve(Eigen::VectorXd::Ones(sys.K.rows()));
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    // mpiexec for the SLEPc peer: Open MPI refuses root without these.
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
    warm_up();
    std::vector<Row> rows;
    for (long size : o.sizes) {
      rows.push_back(run_size(size, o));
      print_tables(rows, o, std::cerr);  // so that a long run reports as it goes
    }
    print_tables(rows, o, std::cout);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_plate_modes: " << e.what() << "\n";
    return 1;
  }
}
