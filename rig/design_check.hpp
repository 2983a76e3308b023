#pragma once
// The designer's check: the rig's first deformation frequency f1 against its
// highest swing frequency. Rigid identification assumes the frames and rods
// do not deform at the swing frequencies; that holds when f1 is at least 4x
// the highest swing frequency, is marginal between 3x and 4x, and fails below.
#include <optional>
#include <string>
#include <vector>

#include "rig/linearization.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::rig {

enum class Verdict { rigid_safe, marginal, use_flexible };
const char* to_string(Verdict v);  // "rigid identification safe", "marginal", "use the flexible algorithm"

enum class Component { fixed_frame, rods, carrying_frame };
const char* to_string(Component c);  // "fixed_frame", "rods", "carrying_frame"

struct CheckOptions {
  double target_ratio = 4.0;
  double marginal_ratio = 3.0;
  void validate() const;
};

// How much stiffer, and where: a factor above 1 on one component's stiffness.
struct StiffnessAdvice {
  Component component = Component::fixed_frame;  // the dominant one in the first deformation mode
  std::optional<double> factor;  // > 1; none when stiffening this component alone cannot do it
  double ratio_limit = 0;        // ratio with that component 1e4 times stiffer (bounded search)
  std::string message;
};

struct CheckResult {
  std::vector<double> swing_frequencies_hz;
  std::optional<double> first_deformation_frequency_hz;  // none when nothing deforms (all rigid)
  std::optional<double> ratio;
  Verdict verdict = Verdict::rigid_safe;
  // Strain energy shares in the first deformation mode (sum 1).
  double share_fixed_frame = 0, share_rods = 0, share_carrying_frame = 0;
  // Set when the ratio misses the target: the factor that brings it there.
  std::optional<StiffnessAdvice> advice;
  Component dominant = Component::fixed_frame;  // largest share in the first deformation mode
  Linearization linearization;
};

CheckResult design_check(const RigModel& model, const CheckOptions& options = {});

// The worse of two verdicts.
Verdict worse(Verdict a, Verdict b);

}  // namespace rigflex::rig
