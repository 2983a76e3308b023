#include "rig/effect_ranges.hpp"

#include <cmath>
#include <sstream>

namespace rigflex::rig {
namespace {

bool is_numeric(ParameterShape s) { return s != ParameterShape::text && s != ParameterShape::map; }

double scale_of(ParameterScale scale, const RangeScales& s) {
  switch (scale) {
    case ParameterScale::absolute:
      return 1.0;
    case ParameterScale::rod_length:
      return s.rod_length;
    case ParameterScale::weight_per_rod:
      return s.weight_per_rod;
    case ParameterScale::body_mass:
      return s.body_mass;
  }
  return NAN;
}

// How a scale is written: its symbol in a range ("0.2 L") and what it is.
struct ScaleWords {
  const char* symbol;
  const char* meaning;
};

ScaleWords words(ParameterScale scale) {
  switch (scale) {
    case ParameterScale::rod_length:
      return {"L", "the rods' mean length"};
    case ParameterScale::weight_per_rod:
      return {"W", "the body's weight over the rods"};
    case ParameterScale::body_mass:
      return {"m_body", "the body's mass"};
    case ParameterScale::absolute:
      break;
  }
  return {"", ""};
}

std::string range_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// One end of a range: its number times the scale's symbol ("0.2 L"; "0",
// not "0 L").
std::string end_text(double x, ParameterScale scale) {
  if (std::isinf(x)) return x < 0 ? "-inf" : "inf";
  if (x == 0 || scale == ParameterScale::absolute) return range_number(x);
  return range_number(x) + " " + words(scale).symbol;
}

// An end multiplied out; infinite where the scale is unknown (NaN) or the
// end is infinite already.
double end_value(double end, const ParameterSpec& spec, const RangeScales& scales, double unknown) {
  if (std::isinf(end) || end == 0) return end;
  const double s = scale_of(spec.scale, scales);
  return std::isfinite(s) && s > 0 ? end * s : unknown;
}

// Each scalar of a (nested) list or a scalar, with the value that holds it.
template <class F>
void for_each_number(const ParameterValue& v, F&& visit) {
  if (v.kind == ParameterValue::Kind::scalar) {
    if (v.number) visit(v, *v.number);
    return;
  }
  for (const auto& item : v.items) for_each_number(item, visit);
}

}  // namespace

RangeScales range_scales(const RigGeometry& geometry, double body_mass) {
  RangeScales s;
  const int n = geometry.rod_count();
  if (n > 0) {
    double length = 0;
    for (const auto& rod : geometry.rods) length += rod.length / n;
    s.rod_length = length;
  }
  if (body_mass > 0) {
    s.body_mass = body_mass;
    if (n > 0) s.weight_per_rod = body_mass * geometry.gravity / n;
  }
  return s;
}

RangeScales range_scales(const EffectParseContext& x) {
  return x.geometry ? range_scales(*x.geometry, x.body_mass) : RangeScales{};
}

double range_low(const ParameterSpec& spec, const RangeScales& scales) {
  return end_value(spec.low, spec, scales, -INFINITY);
}

double range_high(const ParameterSpec& spec, const RangeScales& scales) {
  return end_value(spec.high, spec, scales, INFINITY);
}

std::string range_text(const ParameterSpec& spec) {
  if (!is_numeric(spec.shape) || (std::isinf(spec.low) && std::isinf(spec.high))) return "";
  return std::string(spec.low_open ? "(" : "[") + end_text(spec.low, spec.scale) + ", " +
         end_text(spec.high, spec.scale) + (std::isinf(spec.high) ? ")" : "]");
}

void check_ranges(const EffectKind& kind, const ParameterValue& tree, const RangeScales& scales) {
  for (const ParameterSpec& spec : kind.parameters) {
    if (!is_numeric(spec.shape)) continue;
    const double low = range_low(spec, scales), high = range_high(spec, scales);
    for_each_number(tree[spec.key], [&](const ParameterValue& at, double x) {
      if (!std::isfinite(x)) ParameterReader::fail(at, spec.key, "expected a finite number");
      const bool below = spec.low_open ? !(x > low) : !(x >= low);
      if (!below && x <= high) return;
      std::string why = "'" + (at.text.empty() ? range_number(x) : at.text) + "'" +
                        (spec.unit.empty() || spec.unit == "1" ? "" : " " + spec.unit) +
                        " is outside the physical range " + range_text(spec);
      if (spec.scale != ParameterScale::absolute) {
        why += " = " + std::string(spec.low_open ? "(" : "[") + end_text(low, ParameterScale::absolute) + ", " +
               end_text(high, ParameterScale::absolute) + "]" + (spec.unit == "1" ? "" : " " + spec.unit) + " (" +
               words(spec.scale).symbol + " = " + range_number(scale_of(spec.scale, scales)) + ", " +
               words(spec.scale).meaning + ")";
      }
      ParameterReader::fail(at, spec.key, why + ": a wrong entry, or another unit?");
    });
  }
}

}  // namespace rigflex::rig
