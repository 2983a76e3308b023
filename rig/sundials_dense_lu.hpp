#pragma once
// A SUNDIALS linear solver for CVODE's Newton systems (I - gamma J, dense,
// a few tens of states) by Eigen's partial-pivoting LU. SUNDIALS' own dense
// solver (unblocked, scalar loops) took over half of a rig simulation's time
// at 43 states; Eigen's blocked, vectorized kernels do the same work several
// times faster. Internal to rig/ (SUNDIALS headers are private to it).
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace rigflex::rig {

// Pairs with a SUNDenseMatrix; free with SUNLinSolFree.
SUNLinearSolver make_dense_eigen_solver(SUNContext ctx);

}  // namespace rigflex::rig
