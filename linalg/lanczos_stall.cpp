// diagnose_stall: the order of the tests matters. A mechanism and a
// near-singular shift are faults of the problem, which no larger basis
// cures, so they are named before a cluster that they may also produce.
#include "linalg/lanczos_stall.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace rigflex::linalg {
namespace {

double hz(double lambda) { return std::sqrt(std::max(lambda, 0.0)) / (2.0 * std::numbers::pi); }

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::string progress_text(const StallFacts& f) {
  return "a basis of " + std::to_string(f.basis) + " vectors, block " + std::to_string(f.block) + ", " +
         std::to_string(f.converged) + " of " + std::to_string(f.count) + " pairs converged after " +
         std::to_string(f.restarts) + " restarts";
}

struct Estimates {
  std::vector<double> lambda;    // eigenvalue estimates, ascending (theta descending)
  std::vector<double> relative;  // residual / theta: the Ritz pair's relative accuracy
};

Estimates estimates(const StallFacts& f) {
  Estimates e;
  for (Eigen::Index i = 0; i < f.theta.size(); ++i) {
    if (!(f.theta[i] > 0.0)) continue;  // the infinite eigenvalues of a singular M
    e.lambda.push_back(f.shift + 1.0 / f.theta[i]);
    e.relative.push_back(f.residual[i] / f.theta[i]);
  }
  return e;
}

// The unconverged wanted estimate with the most neighbours within
// kClusterWidth of its distance to the shift; sets cluster_hz and _size.
void find_cluster(const StallFacts& f, const Estimates& e, double zero, EigenStall& s) {
  const auto wanted = std::min<size_t>(static_cast<size_t>(f.count), e.lambda.size());
  for (size_t i = static_cast<size_t>(std::max(f.converged, 0)); i < wanted; ++i) {
    if (std::abs(e.lambda[i]) <= zero) continue;
    const double width = kClusterWidth * (e.lambda[i] - f.shift);
    const auto members =
        std::count_if(e.lambda.begin(), e.lambda.end(), [&](double l) { return std::abs(l - e.lambda[i]) <= width; });
    if (members > s.cluster_size) {
      s.cluster_size = static_cast<int>(members);
      s.cluster_hz = hz(e.lambda[i]);
    }
  }
}

}  // namespace

EigenStall diagnose_stall(const StallFacts& f) {
  EigenStall s;
  const Estimates e = estimates(f);
  const double zero = kZeroEigenvalueFraction * f.scale;
  const auto zeros = std::count_if(e.lambda.begin(), e.lambda.end(), [&](double l) { return std::abs(l) <= zero; });
  if (zeros > kRigidBodyModes) {
    s.cause = StallCause::mechanism;
    s.why = std::to_string(zeros) + " eigenvalue estimates are zero, more than the " + std::to_string(kRigidBodyModes) +
            " rigid-body modes of a free body: a mechanism (" + progress_text(f) + ")";
    s.advice = "support or connect the parts that move freely; a larger basis does not help";
    return s;
  }
  const auto first = std::find_if(e.lambda.begin(), e.lambda.end(), [&](double l) { return std::abs(l) > zero; });
  const size_t top = std::min<size_t>(static_cast<size_t>(f.count), e.lambda.size());
  if (first != e.lambda.end() && top > 0) {
    const double nearest = *first - f.shift;
    const double highest = e.lambda[top - 1] - f.shift;
    if (nearest < kNearSingularShift * highest) {
      s.cause = StallCause::near_singular_shift;
      s.why = "the shift sigma = " + format("%.6g", f.shift) + " (rad/s)^2 lies " + format("%.3g", nearest) +
              " below the eigenvalue at " + format("%.6g Hz", hz(*first)) + ", " + format("%.1e", nearest / highest) +
              " of the wanted range: that direction swamps the others (" + progress_text(f) + ")";
      s.advice = "lower the shift to about " + format("%.3g", 0.1 * highest) +
                 " (rad/s)^2 below the lowest eigenvalue, or leave it to the default";
      return s;
    }
  }
  find_cluster(f, e, zero, s);
  if (s.cluster_size >= kClusterMembers) {
    s.cause = StallCause::clustered;
    s.why = std::to_string(s.cluster_size) + " eigenvalue estimates lie within " +
            format("%g %%", 100 * kClusterWidth) + " of " + format("%.6g Hz", s.cluster_hz) +
            ": shift-invert Lanczos separates eigenvalues by their relative gaps, and these are smaller (" +
            progress_text(f) + ")";
    s.advice = "enlarge the basis (now " + std::to_string(f.basis) + ") to " +
               std::to_string(retry_basis(s, f.count, f.basis, f.block)) + " vectors or more and the block to " +
               std::to_string(retry_block(s, f.block)) +
               "; a cluster of unphysical modes is better removed at its cause";
    return s;
  }
  s.cause = StallCause::slow_convergence;
  s.why = "slow convergence, no cluster or fault of the problem seen";
  if (!e.lambda.empty()) {
    const size_t next = std::min<size_t>(static_cast<size_t>(std::max(f.converged, 0)), e.lambda.size() - 1);
    s.why += ": the lowest unconverged pair, " + format("%.6g Hz", hz(e.lambda[next])) +
             ", has a relative residual of " + format("%.1e", e.relative[next]);
  }
  s.why += " (" + progress_text(f) + ")";
  s.advice = "enlarge the basis (now " + std::to_string(f.basis) + ") to " +
             std::to_string(retry_basis(s, f.count, f.basis, f.block)) + " vectors or more, or raise the restart limit";
  return s;
}

int retry_block(const EigenStall& stall, int block) {
  if (stall.cause != StallCause::clustered) return block;
  return std::max(block, std::min(stall.cluster_size, kMaxRetryBlock));
}

long retry_basis(const EigenStall& stall, int count, int basis, int block) {
  const int b = retry_block(stall, block);
  return std::max(static_cast<long>(kRetryBasisGrowth) * basis, count + 2L * stall.cluster_size + 2L * b);
}

}  // namespace rigflex::linalg
