// SLEPc Krylov-Schur with shift-and-invert on PETSc matrices distributed by
// rows. PETSc reports failures by error codes and an error handler; both are
// turned into the outcome of solve_slepc (a PetscFailure inside this file).
#include "linalg/slepc_eigen.hpp"

#include <mpi.h>
#include <slepceps.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>
#include <vector>

#include "linalg/eigen_postprocess.hpp"

namespace rigflex::linalg {
namespace {

struct PetscFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The first message of the failing call's trace (PETSc calls the handler at
// every level the error passes; the first has the cause, e.g. MUMPS's
// INFOG(1)).
thread_local std::string petsc_message;

PetscErrorCode keep_message(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                            PetscErrorType type, const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) {
    petsc_message = std::string(message ? message : "") + " (in " + (function ? function : "?") + ", " +
                    (file ? file : "?") + ":" + std::to_string(line) + ")";
  }
  return code;
}

void check(PetscErrorCode code, const char* call) {
  if (code == 0) return;
  std::string what = petsc_message;
  if (what.empty()) {
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    what = text ? text : "PETSc error " + std::to_string(static_cast<int>(code));
  }
  petsc_message.clear();
  throw PetscFailure(std::string(call) + ": " + what);
}

// Owners of PETSc objects: destroyed when the solve ends, however it ends.
template <typename T, PetscErrorCode (*Destroy)(T*)>
struct Owned {
  T object = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() {
    if (object) Destroy(&object);
  }
};
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedEps = Owned<EPS, EPSDestroy>;
using OwnedScatter = Owned<VecScatter, VecScatterDestroy>;

struct RowBlock {
  PetscInt begin = 0, end = 0;
};

RowBlock my_rows(PetscInt n) {
  PetscInt local = PETSC_DECIDE, global = n;
  check(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global), "PetscSplitOwnership");
  PetscInt begin = 0;
  MPI_Exscan(&local, &begin, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) begin = 0;  // MPI_Exscan leaves rank 0's result undefined
  return {begin, begin + local};
}

// This rank's rows of the symmetric A (stored whole, so column i is row i).
void distribute(const SpMat& A, RowBlock rows, Mat& B) {
  const PetscInt n = static_cast<PetscInt>(A.rows());
  check(MatCreate(PETSC_COMM_WORLD, &B), "MatCreate");
  check(MatSetSizes(B, rows.end - rows.begin, rows.end - rows.begin, n, n), "MatSetSizes");
  check(MatSetType(B, MATAIJ), "MatSetType");
  std::vector<PetscInt> diagonal_nnz(static_cast<size_t>(rows.end - rows.begin), 0);
  std::vector<PetscInt> off_nnz(diagonal_nnz.size(), 0);
  for (PetscInt i = rows.begin; i < rows.end; ++i) {
    for (SpMat::InnerIterator it(A, i); it; ++it) {
      const bool own = it.index() >= rows.begin && it.index() < rows.end;
      ++(own ? diagonal_nnz : off_nnz)[static_cast<size_t>(i - rows.begin)];
    }
  }
  check(MatSeqAIJSetPreallocation(B, 0, diagonal_nnz.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(B, 0, diagonal_nnz.data(), 0, off_nnz.data()), "MatMPIAIJSetPreallocation");
  std::vector<PetscInt> columns;
  std::vector<PetscScalar> values;
  for (PetscInt i = rows.begin; i < rows.end; ++i) {
    columns.clear();
    values.clear();
    for (SpMat::InnerIterator it(A, i); it; ++it) {
      columns.push_back(static_cast<PetscInt>(it.index()));
      values.push_back(it.value());
    }
    check(MatSetValues(B, 1, &i, static_cast<PetscInt>(columns.size()), columns.data(), values.data(), INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatSetOption(B, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(B, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
}

MatSolverType petsc_solver_type(SlepcDirectSolver s) {
  switch (s) {
    case SlepcDirectSolver::mumps:
      return MATSOLVERMUMPS;
    case SlepcDirectSolver::cholmod:
      return MATSOLVERCHOLMOD;
    case SlepcDirectSolver::petsc:
      return MATSOLVERPETSC;
  }
  return MATSOLVERMUMPS;
}

// SLEPc's monitor, as EigenProgress: restarts, the pairs converged so far.
struct MonitorContext {
  const SlepcOptions* options = nullptr;
  KSP ksp = nullptr;
};

PetscErrorCode report_progress(EPS, PetscInt iteration, PetscInt converged, PetscScalar*, PetscScalar*, PetscReal*,
                               PetscInt, void* context) {
  const auto* c = static_cast<const MonitorContext*>(context);
  EigenProgress p;
  p.restart = static_cast<int>(iteration);
  p.converged = static_cast<int>(std::min<PetscInt>(converged, c->options->count));
  p.wanted = c->options->count;
  PetscInt solves = 0;
  if (KSPGetTotalIterations(c->ksp, &solves) == 0) p.operator_applications = static_cast<long>(solves);
  c->options->progress(p);
  return 0;
}

void configure(EPS eps, const SlepcOptions& options, double shift) {
  check(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
  check(EPSSetType(eps, EPSKRYLOVSCHUR), "EPSSetType");
  // The target below every eigenvalue: the pairs closest to it are the lowest.
  check(EPSSetTarget(eps, shift), "EPSSetTarget");
  check(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
  ST st = nullptr;
  check(EPSGetST(eps, &st), "EPSGetST");
  check(STSetType(st, STSINVERT), "STSetType");
  KSP ksp = nullptr;
  check(STGetKSP(st, &ksp), "STGetKSP");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, petsc_solver_type(options.direct_solver)), "PCFactorSetMatSolverType");
  check(EPSSetDimensions(eps, options.count, options.subspace > 0 ? options.subspace : PETSC_DEFAULT, PETSC_DEFAULT),
        "EPSSetDimensions");
  check(EPSSetTolerances(eps, options.tolerance, options.max_iterations > 0 ? options.max_iterations : PETSC_DEFAULT),
        "EPSSetTolerances");
  // PETSC_OPTIONS may refine any of this (-eps_ncv, -mat_mumps_icntl_*).
  check(EPSSetFromOptions(eps), "EPSSetFromOptions");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The eigenvectors gathered where SlepcGather says: one scatter, built for
// the layout of the first vector and reused for every one (all share it).
class Gatherer {
 public:
  Gatherer(Vec layout, SlepcGather where) {
    if (where == SlepcGather::all)
      check(VecScatterCreateToAll(layout, &scatter_.object, &whole_.object), "VecScatterCreateToAll");
    else
      check(VecScatterCreateToZero(layout, &scatter_.object, &whole_.object), "VecScatterCreateToZero");
  }
  // x into `column` on the ranks that hold it (whose size is the whole
  // vector's; 0 elsewhere).
  void operator()(Vec x, Eigen::Ref<Eigen::VectorXd> column) {
    check(VecScatterBegin(scatter_.object, x, whole_.object, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(scatter_.object, x, whole_.object, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    PetscInt held = 0;
    check(VecGetLocalSize(whole_.object, &held), "VecGetLocalSize");
    if (held != column.size())
      throw PetscFailure("gathered " + std::to_string(held) + " values where " + std::to_string(column.size()) +
                         " were expected");
    if (held == 0) return;
    const PetscScalar* values = nullptr;
    check(VecGetArrayRead(whole_.object, &values), "VecGetArrayRead");
    std::copy(values, values + held, column.data());
    check(VecRestoreArrayRead(whole_.object, &values), "VecRestoreArrayRead");
  }

 private:
  OwnedScatter scatter_;
  OwnedVec whole_;
};

void solve(const SpMat& K, const SpMat& M, const SlepcOptions& options, EigenResult& r) {
  const PetscInt n = static_cast<PetscInt>(K.rows());
  const RowBlock rows = my_rows(n);
  OwnedMat k, m;
  distribute(K, rows, k.object);
  distribute(M, rows, m.object);
  OwnedEps eps;
  check(EPSCreate(PETSC_COMM_WORLD, &eps.object), "EPSCreate");
  check(EPSSetOperators(eps.object, k.object, m.object), "EPSSetOperators");
  configure(eps.object, options, r.shift);
  ST st = nullptr;
  KSP ksp = nullptr;
  check(EPSGetST(eps.object, &st), "EPSGetST");
  check(STGetKSP(st, &ksp), "STGetKSP");
  MonitorContext monitor{&options, ksp};
  if (options.progress) check(EPSMonitorSet(eps.object, report_progress, &monitor, nullptr), "EPSMonitorSet");

  // EPSSetUp factorizes K - sigma M; EPSSolve iterates on the factor.
  auto start = std::chrono::steady_clock::now();
  check(EPSSetUp(eps.object), "EPSSetUp (the factorization of K - sigma M)");
  r.factor_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  check(EPSSolve(eps.object), "EPSSolve");
  r.iteration_seconds = seconds_since(start);

  PetscInt converged = 0, iterations = 0;
  check(EPSGetConverged(eps.object, &converged), "EPSGetConverged");
  check(EPSGetIterationNumber(eps.object, &iterations), "EPSGetIterationNumber");
  r.restarts = static_cast<int>(iterations);
  PetscInt solves = 0;
  check(KSPGetTotalIterations(ksp, &solves), "KSPGetTotalIterations");
  r.operator_applications = static_cast<long>(solves);  // preonly: one iteration per solve

  const PetscInt take = std::min<PetscInt>(converged, options.count);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const bool holds_vectors = options.gather == SlepcGather::all || rank == 0;
  r.eigenvalues.resize(take);
  r.vectors.resize(holds_vectors ? K.rows() : 0, holds_vectors ? take : 0);
  OwnedVec x;
  check(MatCreateVecs(k.object, &x.object, nullptr), "MatCreateVecs");
  Gatherer gather(x.object, options.gather);
  Eigen::VectorXd column(holds_vectors ? K.rows() : 0);
  for (PetscInt i = 0; i < take; ++i) {
    PetscScalar value = 0;
    check(EPSGetEigenpair(eps.object, i, &value, nullptr, x.object, nullptr), "EPSGetEigenpair");
    r.eigenvalues[i] = PetscRealPart(value);
    gather(x.object, column);
    if (holds_vectors) r.vectors.col(i) = column;
  }
  r.converged_count = static_cast<int>(take);
  r.converged = take == options.count;
  if (!r.converged) {
    EPSConvergedReason reason = EPS_CONVERGED_ITERATING;
    check(EPSGetConvergedReason(eps.object, &reason), "EPSGetConvergedReason");
    r.message = "SLEPc Krylov-Schur converged " + std::to_string(take) + " of " + std::to_string(options.count) +
                " pairs in " + std::to_string(iterations) + " restarts (" + EPSConvergedReasons[reason] +
                "); raise the subspace (ncv) or the iterations";
  }
}

}  // namespace

SlepcSession::SlepcSession() {
  check(SlepcInitializeNoArguments(), "SlepcInitialize");
  // rigflex reports errors itself (library code never prints), and the
  // program's own crash reports (sanitizers, core files) stay its own.
  check(PetscPushErrorHandler(keep_message, nullptr), "PetscPushErrorHandler");
  check(PetscPopSignalHandler(), "PetscPopSignalHandler");
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
  MPI_Comm_size(PETSC_COMM_WORLD, &size_);
}

SlepcSession::~SlepcSession() { SlepcFinalize(); }

SlepcDirectSolver parse_slepc_direct_solver(const std::string& name) {
  if (name == "mumps") return SlepcDirectSolver::mumps;
  if (name == "cholmod") return SlepcDirectSolver::cholmod;
  if (name == "petsc") return SlepcDirectSolver::petsc;
  throw std::invalid_argument("direct solver '" + name + "': expected mumps, cholmod or petsc");
}

const char* to_string(SlepcDirectSolver s) {
  switch (s) {
    case SlepcDirectSolver::mumps:
      return "mumps";
    case SlepcDirectSolver::cholmod:
      return "cholmod";
    case SlepcDirectSolver::petsc:
      return "petsc";
  }
  return "?";
}

void SlepcOptions::validate(Eigen::Index n, int ranks) const {
  if (count < 1) throw std::invalid_argument("count must be at least 1, got " + std::to_string(count));
  if (count > n)
    throw std::invalid_argument("count " + std::to_string(count) + " exceeds the " + std::to_string(n) + " DOFs");
  if (!(tolerance > 0 && tolerance < 1))
    throw std::invalid_argument("tolerance must lie in (0, 1), got " + std::to_string(tolerance));
  if (subspace != 0 && (subspace <= count || subspace > n))
    throw std::invalid_argument("subspace " + std::to_string(subspace) + " must exceed count " + std::to_string(count) +
                                " and not exceed the " + std::to_string(n) + " DOFs");
  if (max_iterations < 0) throw std::invalid_argument("max_iterations must not be negative");
  validate_direct_solver(ranks);
}

void SlepcOptions::validate_direct_solver(int ranks) const {
  if (ranks > 1 && direct_solver != SlepcDirectSolver::mumps)
    throw std::invalid_argument(std::string("direct solver ") + to_string(direct_solver) +
                                " runs on one rank only; with " + std::to_string(ranks) + " ranks use mumps");
}

EigenResult solve_slepc(const SpMat& K, const SpMat& M, const SlepcOptions& options) {
  if (K.rows() != K.cols() || M.rows() != K.rows() || M.cols() != K.cols())
    throw std::invalid_argument("solve_slepc: K and M must be square and of the same size");
  int ranks = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  options.validate(K.rows(), ranks);
  EigenResult r;
  r.requested = options.count;
  r.shift = options.shift ? *options.shift : default_shift(K, M);
  try {
    solve(K, M, options, r);
  } catch (const PetscFailure& failure) {
    r.converged = false;
    r.message = std::string("SLEPc/PETSc failed: ") + failure.what();
    r.eigenvalues.resize(0);
    r.vectors.resize(0, 0);
    r.converged_count = 0;
    return r;
  }
  // Rayleigh-Ritz in the span of SLEPc's vectors, as the built-in solver
  // ends: SLEPc's purified vectors of a cluster (a floating frame's six
  // rigid-body modes) are M-orthogonal only to ~1e-8; the Ritz vectors are
  // to rounding, and the Ritz values are Rayleigh quotients. Rank 0's values
  // then go to every rank, so that all agree to the bit.
  if (r.vectors.cols() > 0) {
    const auto start = std::chrono::steady_clock::now();
    r.eigenvalues = rayleigh_ritz(K, M, r.vectors);
    normalize_signs(r.vectors);
    r.iteration_seconds += seconds_since(start);
  }
  if (r.eigenvalues.size() > 0)
    MPI_Bcast(r.eigenvalues.data(), static_cast<int>(r.eigenvalues.size()), MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  if (r.vectors.cols() > 0) check_eigenpairs(K, M, r);
  return r;
}

}  // namespace rigflex::linalg

namespace rigflex::linalg {

EigenBackend slepc_backend(const SlepcOptions& base) {
  return [base](const SpMat& K, const SpMat& M, const EigenOptions& options) {
    SlepcOptions o = base;
    o.count = options.count;
    o.shift = options.shift;
    o.tolerance = options.tolerance;
    o.subspace = options.subspace;
    o.max_iterations = options.max_restarts;
    o.progress = options.progress;
    return solve_slepc(K, M, o);
  };
}

}  // namespace rigflex::linalg
