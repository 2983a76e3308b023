#include "rig/sundials_dense_lu.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <new>

namespace rigflex::rig {
namespace {

struct Content {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  sunindextype last_flag = 0;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

SUNLinearSolver_Type type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }

int setup(SUNLinearSolver S, SUNMatrix A) {
  const sunindextype n = SUNDenseMatrix_Rows(A);
  const Eigen::Map<const Eigen::MatrixXd> a(SUNDenseMatrix_Data(A), n, SUNDenseMatrix_Columns(A));
  Content& c = content(S);
  c.lu.compute(a);
  // A zero pivot is recoverable for CVODE: it retries with a smaller step.
  const auto& d = c.lu.matrixLU().diagonal();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (d(i) == 0.0) {
      c.last_flag = i + 1;
      return SUNLS_LUFACT_FAIL;
    }
  }
  c.last_flag = 0;
  return SUNLS_SUCCESS;
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
  const sunindextype n = N_VGetLength_Serial(b);
  Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(x), n) =
      content(S).lu.solve(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(b), n));
  return SUNLS_SUCCESS;
}

sunindextype last_flag(SUNLinearSolver S) { return content(S).last_flag; }

int free_solver(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  delete static_cast<Content*>(S->content);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver make_dense_eigen_solver(SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) throw std::bad_alloc();
  S->ops->gettype = type;
  S->ops->getid = id;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->lastflag = last_flag;
  S->ops->free = free_solver;
  S->content = new Content;
  return S;
}

}  // namespace rigflex::rig
