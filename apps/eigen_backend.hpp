#pragma once
// --backend lanczos|slepc and --direct-solver for modes and reduce: the
// built-in Lanczos, or SLEPc under MPI (linalg/slepc_eigen.hpp) when this
// rigflex was built with -DRIGFLEX_SLEPC=ON.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "linalg/eigen_solver.hpp"

namespace rigflex::app {

struct BackendArgs {
  std::string backend = "lanczos";
  std::string direct_solver = "mumps";
};

void add_backend_options(CLI::App& cmd, BackendArgs& args);

// The chosen backend for one command's run: with slepc, PETSc and MPI
// initialized for the run's life; only rank 0 prints and writes.
class BackendRun {
 public:
  // gather_on_every_rank: the eigenvectors on every rank (reduce's checks
  // use them there), else on rank 0 only. Throws CLI::ValidationError for
  // a backend this build lacks, std::invalid_argument for a direct solver
  // that cannot run on the ranks given.
  BackendRun(const BackendArgs& args, bool gather_on_every_rank);
  ~BackendRun();
  BackendRun(const BackendRun&) = delete;
  BackendRun& operator=(const BackendRun&) = delete;

  linalg::EigenBackend backend() const { return backend_; }  // empty: the built-in Lanczos
  bool root() const { return rank_ == 0; }
  bool builtin() const { return !backend_; }
  std::string describe() const;  // "SLEPc Krylov-Schur, shift-invert, MUMPS on 2 MPI ranks"

 private:
  struct Session;
  std::unique_ptr<Session> session_;
  linalg::EigenBackend backend_;
  std::string direct_solver_;
  int rank_ = 0, ranks_ = 1;
};

}  // namespace rigflex::app
