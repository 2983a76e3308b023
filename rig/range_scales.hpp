#pragma once
// The rig's sizes that the physical ranges of effect parameters are stated
// in (rig/effect_ranges.hpp); a header of its own because rig_model.hpp's
// effect uncertainty holds refitted values within those ranges.
#include <cmath>

namespace rigflex::rig {

// NaN where unknown, which leaves the ranges' scaled ends unchecked.
struct RangeScales {
  double rod_length = NAN;      // m, the rods' mean length
  double weight_per_rod = NAN;  // N, the body's weight over the rods
  double body_mass = NAN;       // kg
};

}  // namespace rigflex::rig
