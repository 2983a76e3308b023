// The lowest eigenpairs of K x = lambda M x by SLEPc (linalg/slepc_eigen.hpp)
// on matrices read from Matrix Market files: bench_plate_modes' SLEPc peer,
// run under mpiexec on the K and M it writes.
//
// Sample run:
//   mpiexec -n 2 build/bench/slepc_eigs K.mtx M.mtx --count 20 --shift -1e-2 --direct-solver mumps
//   {"ranks": 2, "direct_solver": "mumps", "read_seconds": 0.8, "setup_seconds": 0.9, "solve_seconds": 1.4, ...}
// One JSON line from rank 0: read time (each rank reads both files, as the
// command line's ranks each assemble the model), setup (the factorization
// of K - sigma M), solve (Krylov-Schur), eigen = setup + solve, the
// frequencies, the largest residual ||Kx - lambda Mx|| / ||Kx|| checked on
// rank 0, and the peak resident memory (VmHWM) of the largest rank and of
// all ranks together.
#include <mpi.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/plate_model.hpp"
#include "linalg/slepc_eigen.hpp"

namespace {

using namespace rigflex;

// A `coordinate real symmetric` (lower triangle) or `general` file.
linalg::SpMat read_mtx(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t header_end = text.find('\n');
  const std::string header = text.substr(0, header_end);
  if (header.find("coordinate") == std::string::npos) throw std::runtime_error(file + ": not a coordinate matrix");
  const bool symmetric = header.find("symmetric") != std::string::npos;
  const char* p = text.data() + header_end + 1;
  const char* end = text.data() + text.size();
  while (p < end && *p == '%') p = static_cast<const char*>(std::memchr(p, '\n', static_cast<size_t>(end - p))) + 1;
  auto skip = [&] {
    while (p < end && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')) ++p;
  };
  auto integer = [&] {
    skip();
    long v = 0;
    const auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc()) throw std::runtime_error(file + ": bad integer");
    p = r.ptr;
    return v;
  };
  auto real = [&] {
    skip();
    double v = 0;
    const auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc()) throw std::runtime_error(file + ": bad number");
    p = r.ptr;
    return v;
  };
  const long rows = integer(), cols = integer(), entries = integer();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(symmetric ? 2 * entries : entries));
  for (long k = 0; k < entries; ++k) {
    const long i = integer() - 1, j = integer() - 1;
    const double v = real();
    t.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
    if (symmetric && i != j) t.emplace_back(static_cast<int>(j), static_cast<int>(i), v);
  }
  linalg::SpMat A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(int argc, char** argv, int rank) {
  if (argc < 3)
    throw std::invalid_argument(
        "usage: slepc_eigs K.mtx M.mtx [--count N] [--shift S] [--tol T] "
        "[--direct-solver mumps|cholmod|petsc]");
  linalg::SlepcOptions o;
  o.count = 20;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--count")
      o.count = std::stoi(v);
    else if (a == "--shift")
      o.shift = std::stod(v);
    else if (a == "--tol")
      o.tolerance = std::stod(v);
    else if (a == "--direct-solver")
      o.direct_solver = linalg::parse_slepc_direct_solver(v);
    else
      throw std::invalid_argument("unknown option " + a);
  }
  auto t0 = std::chrono::steady_clock::now();
  const linalg::SpMat K = read_mtx(argv[1]), M = read_mtx(argv[2]);
  const double read = seconds_since(t0);
  const linalg::EigenResult r = linalg::solve_slepc(K, M, o);
  double peak = bench::status_kb("VmHWM:") / 1024.0, peak_max = 0, peak_sum = 0;
  MPI_Reduce(&peak, &peak_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  MPI_Reduce(&peak, &peak_sum, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (rank != 0) return r.converged ? 0 : 1;
  if (!r.converged) {
    std::fprintf(stderr, "slepc_eigs: %s\n", r.message.c_str());
    return 1;
  }
  std::string freqs;
  const Eigen::VectorXd f = r.frequencies_hz();
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    char number[32];
    std::snprintf(number, sizeof number, "%.17g", f[i]);
    freqs += (i ? ", " : "") + std::string(number);
  }
  std::printf(
      "{\"ranks\": %d, \"direct_solver\": \"%s\", \"read_seconds\": %.4f, \"setup_seconds\": %.4f, "
      "\"solve_seconds\": %.4f, \"eigen_seconds\": %.4f, \"restarts\": %d, \"solves\": %ld, \"max_residual\": %.3e, "
      "\"orthogonality_error\": %.3e, \"rss_mb_max_rank\": %.1f, \"rss_mb_all_ranks\": %.1f, "
      "\"frequencies_hz\": [%s]}\n",
      ranks, to_string(o.direct_solver), read, r.factor_seconds, r.iteration_seconds,
      r.factor_seconds + r.iteration_seconds, r.restarts, r.operator_applications, r.residuals.maxCoeff(),
      r.orthogonality_error, peak_max, peak_sum, freqs.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const linalg::SlepcSession session;
  try {
    return run(argc, argv, session.rank());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "slepc_eigs: %s\n", e.what());
    return 2;
  }
}
