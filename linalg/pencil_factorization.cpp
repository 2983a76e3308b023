// Factorization of K - sigma M for shift-invert, with the default shift and
// the distinction between a mechanism (singular for every sigma) and a shift
// that is merely too high.
#include <stdexcept>
#include <string>

#include "linalg/eigen_solver.hpp"
#include "linalg/mechanism.hpp"
#include "linalg/pencil_scale.hpp"

namespace rigflex::linalg {
namespace {

constexpr double kDefaultShiftFactor = 1e-10;
// Retry factor for the default shift when pivots come out at rounding level.
constexpr double kShiftRetryFactor = 1e3;
// On K + s M, which is positive definite unless there is a mechanism, pivots
// come out at worst at 1 / (stiffness contrast); below this we confirm with
// the null-space computation.
constexpr double kMechanismPivot = 1e-11;

// Motions with neither stiffness nor mass (null(K) ∩ null(M)). Reuses the
// factor's analysis for the quick pivot check; overwrites its values.
std::vector<Eigen::Index> find_mechanism(const SpMat& K, const SpMat& M, SparseCholesky& factor) {
  const FactorStatus status = factor.factorize_shifted(K, M, -pencil_scale(K, M));
  if (status.ok && status.min_relative_pivot > kMechanismPivot) return {};
  return mechanism_dofs(K, M);
}

std::string mechanism_message(size_t dofs) {
  return "K - sigma M is singular: mechanism (" + std::to_string(dofs) +
         " DOFs move with neither stiffness nor mass; see mechanism_dofs)";
}

std::string not_definite_message(double sigma, const FactorStatus& status, bool user_shift) {
  std::string text = "K - sigma M is not positive definite at sigma = " + std::to_string(sigma);
  if (status.failed_column >= 0) {
    text += " (non-positive pivot at DOF " + std::to_string(status.failed_column) + ")";
  } else if (!status.message.empty()) {
    text += " (" + status.message + ")";
  }
  text += user_shift ? ": the shift must lie below the lowest eigenvalue"
                     : ": K or M is not positive semidefinite";
  return text;
}

}  // namespace

double default_shift(const SpMat& K, const SpMat& M) {
  return -kDefaultShiftFactor * pencil_scale(K, M);
}

PencilFactorization factorize_pencil(const SpMat& K, const SpMat& M, std::optional<double> shift,
                                     SparseCholesky& factor) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    throw std::invalid_argument("factorize_pencil: K and M must be square and of equal size");
  }
  PencilFactorization out;
  const bool user_shift = shift.has_value();
  out.shift = user_shift ? *shift : default_shift(K, M);
  out.status = factor.factorize_shifted(K, M, out.shift);
  if (out.status.over_memory_limit) {
    out.message = out.status.message;
    return out;
  }
  if (out.status.ok && out.status.min_relative_pivot >= kTinyPivot) {
    out.ok = true;
    return out;
  }
  // Singular to working precision: a mechanism, or (default shift) rigid-body
  // pivots too close to rounding, or (user shift) a shift at or above lambda_1.
  out.mechanism_dofs = find_mechanism(K, M, factor);
  if (!out.mechanism_dofs.empty()) {
    out.message = mechanism_message(out.mechanism_dofs.size());
    return out;
  }
  if (!user_shift) out.shift *= kShiftRetryFactor;
  if (!user_shift || out.status.ok) out.status = factor.factorize_shifted(K, M, out.shift);
  out.ok = out.status.ok;
  out.message = out.ok ? "" : not_definite_message(out.shift, out.status, user_shift);
  return out;
}

}  // namespace rigflex::linalg
