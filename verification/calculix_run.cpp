// Running ccx on a deck and reading its eigenvalues and matrices back.
#include "verification/calculix.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "io/atomic_file.hpp"

extern char** environ;


namespace rigflex::verification {
namespace fs = std::filesystem;

void parse_calculix_eigenvalues(const std::string& dat_text, std::vector<double>& eigenvalues,
                                std::vector<double>& frequencies_hz) {
  eigenvalues.clear();
  frequencies_hz.clear();
  const auto at = dat_text.find("E I G E N V A L U E   O U T P U T");
  if (at == std::string::npos) throw std::runtime_error("no eigenvalue table (E I G E N V A L U E   O U T P U T)");
  std::istringstream in(dat_text.substr(at));
  std::string line;
  std::getline(in, line);  // the title
  // Header lines, then rows "mode  eigenvalue  rad/time  cycles/time  imag";
  // the table ends at the first line that is not such a row.
  while (std::getline(in, line)) {
    std::istringstream row(line);
    long mode = 0;
    double lambda = 0, omega = 0, f = 0, imag = 0;
    if (row >> mode >> lambda >> omega >> f >> imag) {
      eigenvalues.push_back(lambda);
      frequencies_hz.push_back(f);
    } else if (!eigenvalues.empty()) {
      break;
    }
  }
  if (eigenvalues.empty()) throw std::runtime_error("the eigenvalue table has no rows");
}

bool calculix_available(const std::string& executable) {
  if (executable.find('/') != std::string::npos) return ::access(executable.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::istringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    if (::access((fs::path(dir) / executable).c_str(), X_OK) == 0) return true;
  }
  return false;
}

namespace {

std::string tail_of(const fs::path& file, size_t chars) {
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.size() > chars ? "..." + text.substr(text.size() - chars) : text;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Runs argv in `dir` with stdout and stderr to `log`; returns the exit
// status and fills the child's resource usage. Throws if it cannot start.
int run_child(const std::vector<std::string>& argv, const fs::path& dir, const fs::path& log,
              const std::vector<std::string>& extra_env, struct rusage& usage) {
  std::vector<std::string> env_store;
  for (char** e = environ; e && *e; ++e) {
    const std::string kv(*e);
    const std::string key = kv.substr(0, kv.find('='));
    bool overridden = false;
    for (const std::string& x : extra_env) overridden = overridden || x.substr(0, x.find('=')) == key;
    if (!overridden) env_store.push_back(kv);
  }
  for (const std::string& x : extra_env) env_store.push_back(x);
  std::vector<char*> envp, args;
  for (auto& s : env_store) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> argv_store = argv;
  for (auto& s : argv_store) args.push_back(s.data());
  args.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  const std::string log_path = fs::absolute(log).string();
  posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  int status = 0;
  while (::wait4(pid, &status, 0, &usage) < 0) {
    if (errno != EINTR) throw std::runtime_error("waiting for " + argv[0] + " failed: " + std::strerror(errno));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

void check_run_options(const CalculixRunOptions& run) {
  if (run.job.empty() || run.job.find('/') != std::string::npos)
    throw std::invalid_argument("CalculixRunOptions::job must be a plain file name");
  if (run.threads < 0) throw std::invalid_argument("CalculixRunOptions::threads must be non-negative");
}

std::vector<std::string> child_environment(const CalculixRunOptions& run) {
  std::vector<std::string> env;
  if (run.threads > 0) {
    const std::string t = std::to_string(run.threads);
    for (const char* key : {"OMP_NUM_THREADS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_STIFFNESS",
                            "CCX_NPROC_RESULTS", "OPENBLAS_NUM_THREADS"})
      env.push_back(std::string(key) + "=" + t);
  }
  return env;
}

}  // namespace

CalculixFrequencies run_calculix_frequencies(const fe::Model& model, int count, const fs::path& work_dir) {
  return run_calculix_frequencies(model, count, work_dir, CalculixRunOptions{});
}

CalculixFrequencies run_calculix_frequencies(const fe::Model& model, int count, const fs::path& work_dir,
                                             const CalculixRunOptions& run) {
  check_run_options(run);
  CalculixOptions opt;
  opt.modes = count;
  opt.heading = "rigflex cross-check";
  fs::create_directories(work_dir);
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  io::write_text_atomically(work_dir / (run.job + ".inp"), calculix_input(model, opt));
  const double write_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  CalculixFrequencies r = run_calculix_job(work_dir, run);
  r.write_seconds = write_seconds;
  return r;
}

CalculixFrequencies run_calculix_job(const fs::path& work_dir, const CalculixRunOptions& run) {
  check_run_options(run);
  CalculixFrequencies r;
  r.input = work_dir / (run.job + ".inp");
  r.dat = work_dir / (run.job + ".dat");
  r.log = work_dir / (run.job + ".log");
  if (!fs::is_regular_file(r.input)) throw std::runtime_error("CalculiX input " + r.input.string() + " is not there");
  std::error_code ec;
  fs::remove(r.dat, ec);  // never read a stale table

  using clock = std::chrono::steady_clock;
  struct rusage usage {};
  const auto t0 = clock::now();
  const int status = run_child({run.executable, "-i", run.job}, work_dir, r.log, child_environment(run), usage);
  r.wall_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  r.max_rss_kb = usage.ru_maxrss;

  const std::string dat = read_text(r.dat);
  {
    const std::string log = read_text(r.log);
    const auto at = log.find("number of equations");
    if (at != std::string::npos) {
      std::istringstream in(log.substr(at + std::string("number of equations").size()));
      in >> r.equations;
    }
  }
  try {
    if (status != 0) throw std::runtime_error("exit status " + std::to_string(status));
    parse_calculix_eigenvalues(dat, r.eigenvalues, r.frequencies_hz);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("CalculiX run in " + work_dir.string() + " failed (" + e.what() + "); see " +
                             r.log.string() + ":\n" + tail_of(r.log, 1500));
  }
  return r;
}

// ---------------------------------------------------------------------------
// ccx's matrices (SOLVER=MATRIXSTORAGE)

namespace {

// Lines of `text` with their 1-based numbers; blank lines are skipped.
template <typename F>
void for_each_line(const std::string& text, F&& f) {
  size_t start = 0;
  long number = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    ++number;
    std::string_view line(text.data() + start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") != std::string_view::npos) f(line, number);
    start = end + 1;
  }
}

[[noreturn]] void bad_line(const std::string& file, long line, const std::string& what, std::string_view text) {
  throw std::runtime_error(file + ":" + std::to_string(line) + ": " + what + ", got '" +
                           std::string(text.substr(0, 80)) + "'");
}

// The next blank-separated field of `rest`, which is advanced past it.
std::string_view next_field(std::string_view& rest) {
  const size_t b = rest.find_first_not_of(" \t");
  if (b == std::string_view::npos) {
    rest = {};
    return {};
  }
  rest.remove_prefix(b);
  const size_t e = std::min(rest.find_first_of(" \t"), rest.size());
  const std::string_view field = rest.substr(0, e);
  rest.remove_prefix(e);
  return field;
}

template <typename T>
bool parse_whole(std::string_view s, T& value) {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

std::vector<std::pair<long, int>> parse_calculix_dofs(const std::string& text, const std::string& file) {
  std::vector<std::pair<long, int>> dofs;
  for_each_line(text, [&](std::string_view line, long number) {
    std::string_view rest = line;
    const std::string_view field = next_field(rest);
    const size_t dot = field.find('.');
    long node = 0;
    int direction = -1;
    if (!next_field(rest).empty() || dot == std::string_view::npos || !parse_whole(field.substr(0, dot), node) ||
        !parse_whole(field.substr(dot + 1), direction) || node < 1 || direction < 0)
      bad_line(file, number, "expected node.direction", line);
    dofs.emplace_back(node, direction);
  });
  if (dofs.empty()) throw std::runtime_error(file + ": no degrees of freedom");
  return dofs;
}

CalculixSparse parse_calculix_matrix(const std::string& text, Eigen::Index size, const std::string& file) {
  if (size < 1) throw std::invalid_argument("parse_calculix_matrix: size must be positive");
  struct Entry {
    long column, row, line;
  };
  std::vector<Entry> entries;
  std::vector<Eigen::Triplet<double>> triplets;
  entries.reserve(text.size() / 40);
  triplets.reserve(text.size() / 20);
  bool ordered = true;  // ccx sorts by column, then row: then repeats show as a non-increasing pair
  for_each_line(text, [&](std::string_view line, long number) {
    std::string_view rest = line;
    long i = 0, j = 0;
    double v = 0;
    if (!parse_whole(next_field(rest), i) || !parse_whole(next_field(rest), j) ||
        !parse_whole(next_field(rest), v) || !next_field(rest).empty())
      bad_line(file, number, "expected 'row column value'", line);
    if (i < 1 || j < 1 || i > size || j > size)
      bad_line(file, number, "index outside 1.." + std::to_string(size) + " (the size of the .dof file)", line);
    if (i > j) bad_line(file, number, "entry below the diagonal (ccx stores the upper triangle)", line);
    if (!std::isfinite(v)) bad_line(file, number, "value is not finite", line);
    if (!entries.empty()) {
      const Entry& p = entries.back();
      ordered = ordered && (j > p.column || (j == p.column && i > p.row));
    }
    entries.push_back({j, i, number});
    triplets.emplace_back(i - 1, j - 1, v);
    if (i != j) triplets.emplace_back(j - 1, i - 1, v);
  });
  if (entries.empty()) throw std::runtime_error(file + ": no matrix entries");
  if (!ordered) {
    std::vector<Entry> sorted = entries;
    std::stable_sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) {
      return a.column != b.column ? a.column < b.column : a.row < b.row;
    });
    for (size_t k = 1; k < sorted.size(); ++k)
      if (sorted[k].column == sorted[k - 1].column && sorted[k].row == sorted[k - 1].row)
        throw std::runtime_error(file + ":" + std::to_string(std::max(sorted[k].line, sorted[k - 1].line)) +
                                 ": entry (" + std::to_string(sorted[k].row) + ", " +
                                 std::to_string(sorted[k].column) + ") repeated (first on line " +
                                 std::to_string(std::min(sorted[k].line, sorted[k - 1].line)) + ")");
  }
  CalculixSparse a(size, size);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

std::optional<Eigen::Index> CalculixMatrices::row_of(fe::NodeId node, int direction) const {
  std::optional<Eigen::Index> found;
  std::array<int, 4> count{};
  for (size_t r = 0; r < dofs.size(); ++r) {
    const CalculixDof& d = dofs[r];
    if (d.origin != CalculixNodeOrigin::model || d.model_node != node) continue;
    if (d.direction >= 0 && d.direction < 4) ++count[static_cast<size_t>(d.direction)];
    if (d.direction == direction) found = static_cast<Eigen::Index>(r);
  }
  // A direction labelled twice means expanded nodes (see the header): then
  // even a direction labelled once may be a DOF of an expanded node.
  for (int c : count)
    if (c > 1) return std::nullopt;
  return found;
}

CalculixMatrices run_calculix_matrices(const fe::Model& model, const fs::path& work_dir) {
  return run_calculix_matrices(model, work_dir, CalculixRunOptions{});
}

CalculixMatrices run_calculix_matrices(const fe::Model& model, const fs::path& work_dir,
                                       const CalculixRunOptions& run) {
  check_run_options(run);
  CalculixOptions opt;
  opt.modes = 1;
  opt.heading = "rigflex matrix export";
  opt.matrix_storage = true;
  const CalculixDeck deck = calculix_deck(model, opt);

  CalculixMatrices r;
  fs::create_directories(work_dir);
  r.input = work_dir / (run.job + ".inp");
  r.stiffness = work_dir / (run.job + ".sti");
  r.mass = work_dir / (run.job + ".mas");
  r.dof_file = work_dir / (run.job + ".dof");
  r.log = work_dir / (run.job + ".log");
  io::write_text_atomically(r.input, deck.text);
  for (const fs::path& p : {r.stiffness, r.mass, r.dof_file}) {
    std::error_code ec;
    fs::remove(p, ec);  // never read stale matrices
  }

  struct rusage usage {};
  const auto t0 = std::chrono::steady_clock::now();
  const int status = run_child({run.executable, "-i", run.job}, work_dir, r.log, child_environment(run), usage);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto failed = [&](const std::string& why) {
    return std::runtime_error("CalculiX run in " + work_dir.string() + " failed (" + why + "); see " +
                              r.log.string() + ":\n" + tail_of(r.log, 1500));
  };
  if (status != 0) throw failed("exit status " + std::to_string(status));
  for (const fs::path& p : {r.stiffness, r.mass, r.dof_file})
    if (!fs::exists(p)) throw failed("no " + p.filename().string() + " written");

  std::unordered_map<long, fe::NodeId> model_node;
  for (const auto& [id, ccx] : deck.ccx_ids) model_node.emplace(ccx, id);
  const long first_generated = deck.first_free_node;
  for (const auto& [node, direction] : parse_calculix_dofs(read_text(r.dof_file), r.dof_file.string())) {
    CalculixDof d;
    d.ccx_node = node;
    d.direction = direction;
    if (const auto it = model_node.find(node); it != model_node.end()) {
      d.origin = CalculixNodeOrigin::model;
      d.model_node = it->second;
    } else {
      d.origin = node < first_generated ? CalculixNodeOrigin::writer : CalculixNodeOrigin::ccx;
    }
    r.dofs.push_back(d);
  }
  const auto n = static_cast<Eigen::Index>(r.dofs.size());
  r.K = parse_calculix_matrix(read_text(r.stiffness), n, r.stiffness.string());
  r.M = parse_calculix_matrix(read_text(r.mass), n, r.mass.string());
  return r;
}

}  // namespace rigflex::verification
