// Validation of EigenOptions and small EigenResult helpers.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "linalg/eigen_solver.hpp"

namespace rigflex::linalg {
namespace {

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("EigenOptions: " + message);
}

}  // namespace

void EigenOptions::validate(Eigen::Index n) const {
  require(n >= 1, "the problem has no DOFs");
  require(count >= 1, "count must be at least 1 (got " + std::to_string(count) + ")");
  require(count <= n, "count (" + std::to_string(count) + ") exceeds the number of DOFs (" +
                          std::to_string(n) + ")");
  require(std::isfinite(tolerance) && tolerance > 0.0 && tolerance < 1.0,
          "tolerance must lie in (0, 1) (got " + std::to_string(tolerance) + ")");
  require(!shift || std::isfinite(*shift), "shift must be finite");
  require(block_size >= 0, "block_size must be 0 (automatic) or at least 1 (got " + std::to_string(block_size) + ")");
  require(block_size <= n, "block_size (" + std::to_string(block_size) +
                               ") exceeds the number of DOFs (" + std::to_string(n) + ")");
  // An automatic block size falls back to 1 when a given subspace lacks room
  // for it (resolved_block).
  const int least_block = std::max(block_size, 1);
  require(subspace == 0 || subspace >= count + least_block,
          "subspace must be 0 (automatic) or at least count + block_size (" +
              std::to_string(count + least_block) + "), got " + std::to_string(subspace));
  require(max_restarts >= 0, "max_restarts must not be negative");
  require(dense_threshold >= 0, "dense_threshold must not be negative");
  require(std::isfinite(max_factor_bytes) && max_factor_bytes >= 0.0,
          "max_factor_bytes must be 0 (no limit) or a positive number of bytes");
}

int EigenOptions::resolved_block(Eigen::Index n, double factor_nnz) const {
  if (block_size > 0) return block_size;
  const int automatic = automatic_block_size(n, factor_nnz, count);
  return subspace == 0 || subspace >= count + 2 * automatic ? automatic : 1;
}

int EigenOptions::resolved_subspace(Eigen::Index n, int block) const {
  if (subspace > 0) return subspace;
  const long automatic = std::max({2L * count, count + 20L, count + 2L * block});
  // A basis larger than n cannot be M-orthonormal; Lanczos stops earlier
  // (the Krylov space becomes invariant), but it needs room for count
  // vectors plus one block in any case.
  return static_cast<int>(std::max<long>(std::min<long>(automatic, n), count + block));
}

double application_words(Eigen::Index n, double factor_nnz, int count) {
  EigenOptions single;
  single.count = count;
  const double basis = single.resolved_subspace(n, 1);
  return factor_nnz + static_cast<double>(n) * basis;
}

int automatic_block_size(Eigen::Index n, double factor_nnz, int count) {
  if (n < 8L * kAutomaticBlock) return 1;
  return application_words(n, factor_nnz, count) >= kAutomaticBlockWords ? kAutomaticBlock : 1;
}

Eigen::VectorXd EigenResult::frequencies_hz() const {
  return eigenvalues.unaryExpr(
      [](double lambda) { return std::sqrt(std::max(lambda, 0.0)) / (2.0 * std::numbers::pi); });
}

}  // namespace rigflex::linalg
