#pragma once
// What identification would make of a rig: simulate a measurement of the
// rig as modelled (random releases, sensor noise), identify it with the
// rigid and/or the flexible algorithm, and compare with the body the model
// carries. The design check's predicted error and the sensitivity sweep are
// this at one rig and at many.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "identify/identification.hpp"
#include "rig/rig_system.hpp"

namespace rigflex::identify {

struct VirtualStudyOptions {
  int sets = 3;
  int histories = 6;
  double duration_s = 15.0;
  std::uint64_t seed = 1;
  IdentificationOptions identification;
  std::function<void(int set, int history)> progress;  // while simulating
  void validate() const;
};

// What one algorithm made of the virtual sets.
struct VirtualOutcome {
  bool observable = true;                 // every set
  std::vector<std::string> unobservable;  // of the first set that was not
  std::string message;
  std::vector<fe::MassProperties> found;  // per set (empty when not observable)
};

struct VirtualStudy {
  fe::MassProperties truth;
  std::optional<VirtualOutcome> rigid, flexible;
};

// `truth` simulates; the identification rigs identify (either may be null).
// Throws NoEquilibrium when the rig finds no static equilibrium.
VirtualStudy virtual_identification(const rig::RigSystem& truth, const IdentificationRig* rigid,
                                    const IdentificationRig* flexible, const VirtualStudyOptions& options);

// Errors of `found` against per-set references (the truth, or another
// algorithm's result on the same data, which cancels most of the noise).
struct ErrorSummary {
  int sets = 0;
  double zG_mean_m = 0, zG_std_m = 0;            // found - reference; std over the sets (0 for one set)
  std::array<double, 3> moment_mean{}, moment_std{};  // (J - J_ref) / J_ref for Jxx, Jyy, Jzz
  double product_max = 0;                        // max |J_ij - ref| / largest reference moment over sets and products
  double cog_in_plane_max_m = 0;                 // max |xG, yG difference| over the sets
};
ErrorSummary summarize_errors(const std::vector<fe::MassProperties>& found,
                              const std::vector<fe::MassProperties>& reference);
ErrorSummary summarize_errors(const std::vector<fe::MassProperties>& found, const fe::MassProperties& reference);

}  // namespace rigflex::identify
