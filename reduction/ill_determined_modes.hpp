#pragma once
// Modes whose frequency double precision cannot give to a part in a
// million. Forming K x rounds by about eps ||K|| ||x||, so an eigenvalue
// lambda is determined to about eps lambda_max / lambda (relative) at best,
// in any solver: a model that joins very stiff and very soft parts (a stiff
// bracket on a soft mount, kilometres of slender beam) leaves its lowest
// eigenvalues undetermined beyond a few digits. Each pair's residual ratio
// ||K x - lambda M x|| / ||K x|| (linalg::EigenResult::residuals) reads that
// level: for x' M x = 1 an eigenvalue lies within ||M^-1/2 r|| of lambda
// (Krylov-Bogoliubov), which the ratio approximates relative to lambda
// where the mass is spread evenly. A frequency carries half the eigenvalue's
// relative error.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fe/assembly.hpp"
#include "reduction/modal_analysis.hpp"
#include "reduction/zero_frequency_modes.hpp"

namespace rigflex::reduction {

struct IllDeterminedMode {
  Eigen::Index mode = 0;  // 0-based index in the result
  double frequency_hz = 0;
  double relative_error = 0;  // estimated |df| / f: half the residual ratio
};

// 1e-6: a million times the rounding unit, a thousand times what a
// well-conditioned frame reaches (1e-12 .. 1e-10 on the plates and frames
// of docs/eigen-solver.md), and below any frequency a test rig's designer
// reads.
inline constexpr double kFrequencyAccuracy = 1e-6;

// The modes of `a` whose estimated relative frequency error exceeds
// `limit`, lowest first; the modes of zero frequency (`zero`, as
// zero_frequency_modes finds them: a free model's rigid-body motions) are
// left out, their ratio measures rounding, not an eigenvalue.
std::vector<IllDeterminedMode> ill_determined_modes(const ModalAnalysis& a, const std::vector<ZeroFrequencyMode>& zero,
                                                    double limit = kFrequencyAccuracy);

// max K_ii / M_ii over the DOFs with mass: a lower bound of lambda_max.
double stiffest_ratio(const fe::AssembledSystem& s);

// One line: which modes, how far their frequencies can be trusted, why and
// what to do.
std::string describe(const std::vector<IllDeterminedMode>& modes, const ModalAnalysis& a);

}  // namespace rigflex::reduction
