#pragma once
// The MPI eigen backend: the same generalized problem K x = lambda M x as
// solve_lanczos (eigen_solver.hpp), solved by SLEPc's Krylov-Schur with
// shift-and-invert on a distributed direct factorization of K - sigma M
// (MUMPS across ranks, or CHOLMOD / PETSc's own Cholesky on one rank).
// Built with -DRIGFLEX_SLEPC=ON (target rigflex::linalg_slepc); run under mpiexec.
//
// Distribution: every rank holds the whole K and M (the model is assembled
// serially on each rank, as rigflex's assembly is) and hands PETSc its own
// block of rows; the factorization, the solves and the Krylov basis - the
// memory that grows past one machine - are distributed. The eigenvectors are
// gathered on rank 0 (or on every rank), where the pairs are checked against
// K and M independently of SLEPc (check_eigenpairs), exactly as the built-in
// solver's are.
#include <functional>
#include <optional>
#include <string>

#include "linalg/eigen_solver.hpp"

namespace rigflex::linalg {

// PETSc and SLEPc initialized for the life of the object (MPI too, if it was
// not), finalized by the destructor. One per process, created before any
// solve_slepc call and destroyed after the last. PETSc reads its options
// from the PETSC_OPTIONS environment variable (e.g. "-eps_view" or
// "-mat_mumps_icntl_14 50"), never from the program's own command line.
// Errors inside PETSc are returned to rigflex, which reports them; PETSc
// prints nothing of its own.
class SlepcSession {
 public:
  SlepcSession();
  ~SlepcSession();
  SlepcSession(const SlepcSession&) = delete;
  SlepcSession& operator=(const SlepcSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

enum class SlepcDirectSolver {
  mumps,    // distributed multifrontal Cholesky: any number of ranks
  cholmod,  // SuiteSparse CHOLMOD inside PETSc (the built-in solver's factorization): one rank only
  petsc,    // PETSc's own sequential Cholesky: one rank only
};
// "mumps", "cholmod", "petsc"; throws std::invalid_argument naming the choices.
SlepcDirectSolver parse_slepc_direct_solver(const std::string& name);
const char* to_string(SlepcDirectSolver s);

enum class SlepcGather {
  root,  // the eigenvectors on rank 0 only (other ranks get the eigenvalues)
  all,   // on every rank
};

struct SlepcOptions {
  int count = 10;               // wanted lowest eigenpairs
  std::optional<double> shift;  // sigma in (rad/s)^2; default default_shift(K, M), as solve_lanczos
  double tolerance = 1e-10;     // SLEPc's relative residual tolerance
  int subspace = 0;             // ncv, 0 = SLEPc's default (max(2 count, count + 15))
  int max_iterations = 0;       // Krylov-Schur restarts, 0 = SLEPc's default
  SlepcDirectSolver direct_solver = SlepcDirectSolver::mumps;
  SlepcGather gather = SlepcGather::root;
  std::function<void(const EigenProgress&)> progress;  // optional, called on every rank

  // Throws std::invalid_argument naming the offending option. `ranks`: the
  // solvers that run on one rank only are refused on more.
  void validate(Eigen::Index n, int ranks) const;
  // The part of validate that needs no problem: the direct solver on `ranks`.
  void validate_direct_solver(int ranks) const;
};

// Lowest options.count eigenpairs of (K, M). Collective: every rank of
// PETSC_COMM_WORLD calls it with the same K, M and options, inside a
// SlepcSession. The result matches EigenResult's contract on rank 0 (and on
// every rank with SlepcGather::all): ascending eigenvalues, M-orthonormal
// vectors with the largest component positive, residuals, backward errors
// and orthogonality checked independently (the values are Rayleigh
// quotients of SLEPc's vectors, after a Rayleigh-Ritz step in their span
// as the built-in solver ends with, the same on every rank). On other ranks with
// SlepcGather::root: the eigenvalues and the outcome, no vectors.
// A failure inside PETSc (a singular factorization, MUMPS out of memory)
// is an outcome: converged = false, message saying what PETSc reported.
// Throws std::invalid_argument for invalid options or sizes only.
EigenResult solve_slepc(const SpMat& K, const SpMat& M, const SlepcOptions& options);

// The backend for callers of EigenBackend (modes, Craig-Bampton's
// fixed-interface modes): EigenOptions' count, shift, tolerance, subspace
// (as ncv), max_restarts (as iterations) and progress (from SLEPc's monitor:
// the restart and the pairs converged) over `base`'s direct solver and
// gather. The Lanczos-only options (block size, multiplicity verification,
// automatic retry, the factor's memory limit) do not apply.
EigenBackend slepc_backend(const SlepcOptions& base);

}  // namespace rigflex::linalg
