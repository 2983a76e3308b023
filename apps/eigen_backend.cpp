#include "apps/eigen_backend.hpp"

#ifdef RIGFLEX_HAVE_SLEPC
#include "linalg/slepc_eigen.hpp"
#endif

namespace rigflex::app {

#ifdef RIGFLEX_HAVE_SLEPC
struct BackendRun::Session {
  linalg::SlepcSession slepc;
};
#else
struct BackendRun::Session {};
#endif

void add_backend_options(CLI::App& cmd, BackendArgs& args) {
  cmd.add_option("--backend", args.backend,
                 "eigen solver: lanczos (built in, default) or slepc (SLEPc Krylov-Schur under MPI: run with "
                 "mpiexec -n RANKS; docs/eigen-solver.md)")
      ->check(CLI::IsMember({"lanczos", "slepc"}));
  cmd.add_option("--direct-solver", args.direct_solver,
                 "with --backend slepc: the factorization of K - sigma M: mumps (any number of ranks, default), "
                 "cholmod or petsc (one rank)")
      ->check(CLI::IsMember({"mumps", "cholmod", "petsc"}));
}

BackendRun::BackendRun(const BackendArgs& args, bool gather_on_every_rank) : direct_solver_(args.direct_solver) {
  if (args.backend == "lanczos") return;
#ifdef RIGFLEX_HAVE_SLEPC
  session_ = std::make_unique<Session>();
  rank_ = session_->slepc.rank();
  ranks_ = session_->slepc.size();
  linalg::SlepcOptions base;
  base.direct_solver = linalg::parse_slepc_direct_solver(args.direct_solver);
  base.gather = gather_on_every_rank ? linalg::SlepcGather::all : linalg::SlepcGather::root;
  base.validate_direct_solver(ranks_);  // before any work
  backend_ = linalg::slepc_backend(base);
#else
  (void)gather_on_every_rank;
  throw CLI::ValidationError("--backend",
                             "slepc: this rigflex was built without the MPI backend; configure with "
                             "-DRIGFLEX_SLEPC=ON (Debian: slepc-dev, petsc-dev)");
#endif
}

BackendRun::~BackendRun() = default;

std::string BackendRun::describe() const {
  if (builtin()) return "built-in shift-invert Lanczos";
  std::string solver = direct_solver_ == "mumps"     ? "MUMPS"
                       : direct_solver_ == "cholmod" ? "CHOLMOD"
                                                     : "PETSc's Cholesky";
  return "SLEPc Krylov-Schur, shift-invert, " + solver + " on " + std::to_string(ranks_) + " MPI rank" +
         (ranks_ == 1 ? "" : "s");
}

}  // namespace rigflex::app
