#pragma once
// The physical ranges of an effect's parameters as a rig or effects file
// states them (rig::ParameterSpec::low, high, scale): the check every file
// goes through before its effect is built, the range a refitted value is
// held in, and the range's words for messages and the docs' tables.
// A value outside is no effect of that kind but a wrong entry or a unit
// slip (a length error of a third of the rod, a gain of 1000 for kN read as
// N); diagnose's plausible ranges (rig::FitParameter) are narrower.
#include <string>

#include "rig/effect_kinds.hpp"
#include "rig/range_scales.hpp"

namespace rigflex::rig {

RangeScales range_scales(const RigGeometry& geometry, double body_mass);
RangeScales range_scales(const EffectParseContext& x);  // NaN without a geometry

// [low, high] of `spec` in its unit for this rig: the scaled ends
// multiplied out; an end whose scale is unknown is infinite.
double range_low(const ParameterSpec& spec, const RangeScales& scales);
double range_high(const ParameterSpec& spec, const RangeScales& scales);

// "[-0.2 L, 0.2 L]", "(0, inf)", "[0.5, 2]"; "" for a range without ends
// or a parameter that is not a number.
std::string range_text(const ParameterSpec& spec);

// Every number that `tree` (an effect's parameters, `uncertainty` taken
// out) gives for a key of `kind` within that key's range; else
// ParameterError naming the number's line, the key and the range.
void check_ranges(const EffectKind& kind, const ParameterValue& tree, const RangeScales& scales);

}  // namespace rigflex::rig
