#include "apps/work_estimate.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "io/input_error.hpp"

namespace rigflex::app {
namespace {

// An assumed rate of CHOLMOD's supernodal factorization on two cores with
// OpenBLAS, on the low side: the 100k-DOF bench plate's 1.7e9 flops take
// 1.1-1.3 s with the ordering. Only the order of the time is promised; the
// flop count printed beside it is exact.
constexpr double kFactorFlopsPerSecond = 3e9;

// Below this many elements the assembly takes well under a second (20 000
// four-node shells, 122k DOFs: 1.7 s on two busy cores): no progress line.
constexpr long kElementsWorthProgress = 10000;

std::string format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

}  // namespace

double memory_limit_bytes(std::optional<double> max_memory_gib) {
  if (max_memory_gib) return *max_memory_gib * 1073741824.0;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

std::string assembly_line(const fe::AssemblySize& size) {
  return "assembling " + std::to_string(size.dofs) + " DOFs, " + format("%.3g", size.nonzeros) +
         " nonzeros in K, about " + fe::bytes_text(size.bytes);
}

std::string factor_line(const linalg::FactorStatistics& s) {
  const double seconds = s.factor_flops / kFactorFlopsPerSecond;
  return "factorizing: " + format("%.3g", s.factor_nnz) + " nonzeros in L, " + fe::bytes_text(s.factor_bytes_estimate) +
         ", " + format("%.3g", s.factor_flops) + " flops (about " +
         (seconds < 1 ? std::string("1 s or less") : format("%.0f s", std::ceil(seconds))) + " per factorization)";
}

std::string memory_refusal(const std::string& why) {
  return why + " (--max-memory, default the machine's memory); nothing written";
}

std::function<void(long, long)> assembly_progress(const std::string& prefix) {
  return [prefix](long done, long total) {
    if (total < kElementsWorthProgress) return;
    std::fprintf(stderr, "\r%sassembled %ld of %ld elements", prefix.c_str(), done, total);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  };
}

io::RigReadOptions frame_reduction_options(const std::string& command, bool quiet) {
  io::RigReadOptions o;
  o.max_bytes = memory_limit_bytes(std::nullopt);
  if (quiet) return o;
  const std::string prefix = command + ": frame reduction: ";
  o.progress = [prefix](const std::string& s) { std::fprintf(stderr, "%s%s\n", prefix.c_str(), s.c_str()); };
  o.analyzed = [prefix](const linalg::FactorStatistics& s) {
    std::fprintf(stderr, "%s%s\n", prefix.c_str(), factor_line(s).c_str());
  };
  o.assembly_progress = assembly_progress(prefix);
  return o;
}

void announce_assembly(const std::string& model_file, const fe::Model& model, double limit_bytes, bool quiet,
                       const std::string& prefix) {
  const fe::AssemblySize size = fe::assembly_size(model);
  if (const std::string refusal = fe::assembly_refusal(size, limit_bytes); !refusal.empty()) {
    throw io::InputError(model_file, 0, "", memory_refusal(refusal));
  }
  if (!quiet) std::fprintf(stderr, "%s%s\n", prefix.c_str(), assembly_line(size).c_str());
}

}  // namespace rigflex::app
