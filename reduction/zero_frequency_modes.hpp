#pragma once
// Modes of zero frequency in a solved modal analysis. In a free model they
// are its rigid-body motions and expected; in a supported one (supports or
// springs to ground) each is a mechanism - a part that can move without
// straining anything - and the frequencies above it describe a structure
// the user did not mean to build. A mechanism with mass factorizes fine and
// converges like any mode, so it must be looked for in the eigenvalues.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fe/model.hpp"
#include "reduction/modal_analysis.hpp"

namespace rigflex::reduction {

struct ZeroFrequencyMode {
  Eigen::Index mode = 0;  // 0-based index in the result
  double frequency_hz = 0;
  // The DOFs that move most ("node 3 RX"), largest first, at most
  // `kListed`; `moving` counts all that move by more than a tenth of the
  // largest (rotations weighed by the model's size, so that they compare
  // with translations).
  std::vector<std::string> largest;
  Eigen::Index moving = 0;
  std::vector<fe::NodeId> nodes;  // the nodes of those moving DOFs, each once, largest motion first
};

inline constexpr size_t kListed = 8;
// |eigenvalue| at or below this share of the pencil's scale (the mean
// K_ii / M_ii) is zero: about 4500 x rounding. For steel frames meshed at
// 1 m to 0.1 m that is a frequency of 0.01-0.1 Hz, an order of magnitude
// below any rig frame's.
inline constexpr double kZeroEigenvalueShare = 1e-12;

std::vector<ZeroFrequencyMode> zero_frequency_modes(const fe::Model& model, const ModalAnalysis& a,
                                                    double share = kZeroEigenvalueShare);

// Held in place: a support, or a spring to the ground.
bool is_supported(const fe::Model& model);

}  // namespace rigflex::reduction
