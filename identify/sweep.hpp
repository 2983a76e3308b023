#pragma once
// The sensitivity sweep of the reference study: scale the suspended mass
// (inertia by the same ratio) at nominal stiffness, and the stiffness of
// frames and rods at nominal mass; at each point the rig's first deformation
// frequency f1 and the errors of zG and Jyy from the rigid and the flexible
// algorithm on virtual measurements. Identification error grows steeply once
// f1 falls below 3-4x the highest swing frequency.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rig/rig_model.hpp"
#include "identify/virtual_identification.hpp"

namespace rigflex::identify {

// count values from start to stop, evenly spaced in log (scales multiply).
struct ScaleRange {
  double start = 1.0, stop = 1.0;
  int count = 1;
  std::vector<double> values() const;
  void validate(const std::string& name) const;  // std::invalid_argument naming the option
};

struct SweepOptions {
  ScaleRange mass{0.1, 1.0, 10};
  ScaleRange stiffness{1.0, 10.0, 10};
  VirtualStudyOptions study{9, 6, 15.0, 1, {}, {}};
  int threads = 0;  // points in parallel; 0: all cores
  std::function<void(int done, int total)> progress;
  void validate() const;
};

enum class SweepKind { mass, stiffness };
const char* to_string(SweepKind k);

struct SweepPoint {
  SweepKind kind = SweepKind::mass;
  double scale = 1.0;
  std::optional<double> f1_hz, swing_max_hz, ratio;  // f1 none: nothing deforms
  std::optional<ErrorSummary> rigid, flexible;       // none when the point failed
  std::string failure;                               // why (no static equilibrium ...)
};

std::vector<SweepPoint> sweep(const rig::RigModel& model, const SweepOptions& options);

}  // namespace rigflex::identify
