#pragma once
// Why a shift-invert Lanczos run stopped short of its wanted pairs, read
// from the Ritz values it ended with, and what to change.
#include <Eigen/Core>

#include "linalg/eigen_solver.hpp"

namespace rigflex::linalg {

struct StallFacts {
  double shift = 0;          // sigma, (rad/s)^2
  Eigen::VectorXd theta;     // the last Ritz values of (K - sigma M)^-1 M, descending
  Eigen::VectorXd residual;  // their residual norms
  int count = 0;             // wanted pairs
  int converged = 0;         // leading wanted pairs converged
  int basis = 0, block = 1, restarts = 0;
  double scale = 1;  // pencil_scale(K, M): what "zero" is measured against
};

// Eigenvalue estimates below this fraction of the pencil's scale are zero:
// the default shift puts rigid-body modes at ~1e-10 of it, rounding keeps
// them there; the lowest flexible mode of a structure sits many decades
// above.
inline constexpr double kZeroEigenvalueFraction = 1e-8;
// Ritz values whose distances to the shift differ by less than this fraction
// form a cluster: shift-invert Lanczos converges at a rate set by these
// relative gaps, and below 1e-3 the default basis needs hundreds of restarts.
inline constexpr double kClusterWidth = 1e-3;
// A cluster: at least this many Ritz values within kClusterWidth.
inline constexpr int kClusterMembers = 3;
// The shift is near-singular when the lowest flexible eigenvalue's distance
// to it is below this fraction of the highest wanted one's.
inline constexpr double kNearSingularShift = 1e-8;
// The automatic retry after a cluster or slow convergence takes this many
// times the basis (see retry_on_factor in lanczos.cpp for why four) and a
// block as large as the cluster, up to kMaxRetryBlock.
inline constexpr int kRetryBasisGrowth = 4;
inline constexpr int kMaxRetryBlock = 8;
// A free body has six rigid-body modes; more zero eigenvalues are a mechanism.
inline constexpr int kRigidBodyModes = 6;

// The cause, a sentence on what was seen and one on what to do.
EigenStall diagnose_stall(const StallFacts& facts);

// The block and the basis of the retry after `stall` (and of the advice,
// which names the same): the cluster's size up to kMaxRetryBlock, not below
// `block`; kRetryBasisGrowth times `basis`, with room beside the `count`
// wanted pairs for two copies of the cluster and two retry blocks.
int retry_block(const EigenStall& stall, int block);
long retry_basis(const EigenStall& stall, int count, int basis, int block);

}  // namespace rigflex::linalg
