#pragma once
// The plausible range of each physical quantity a reader takes. A number
// outside it is a typing or unit slip far more often than a real rig: a
// modulus in MPa (2.1e5), a density in t/mm^3 (7.85e-9), coordinates in
// millimetres. Such a value is finite, so it passes every type check, and
// then overflows or silently scales the answer (a modulus of 1e308 gives a
// mass of NaN). The bounds are wide - a few orders of magnitude around any
// structure a pendulum rig or its body can be made of - and the message
// says how far off the value is and from what, so the unit slip shows.
#include <string>

namespace rigflex::io {

struct PhysicalRange {
  const char* quantity;      // "Young's modulus"
  const char* unit;          // "Pa"
  double lo, hi;             // plausible values, inclusive
  const char* typical_name;  // "steel"
  double typical;            // 2.1e11
  bool magnitude = false;    // bounds apply to |x| (coordinates): lo <= |x| <= hi, or x = 0
};

// "" when x lies in the range, else the reason, e.g. "Young's modulus in Pa
// expected: 2.1e+05 is 6 orders of magnitude below steel (2.1e+11) - units?
// (plausible: 1e+06 to 2e+12 Pa)".
std::string range_problem(double x, const PhysicalRange& r);

namespace ranges {
// Up to 1e15: a link made "rigid" by a modulus 1000 x steel's is a common
// modelling habit; the slips this catches are MPa and GPa, and overflow.
inline constexpr PhysicalRange youngs_modulus{"Young's modulus", "Pa", 1e6, 1e15, "steel", 2.1e11};
inline constexpr PhysicalRange density{"density", "kg/m^3", 10.0, 3e4, "steel", 7850.0};
inline constexpr PhysicalRange coordinate{"a coordinate", "m", 0.0, 1e3, "a rig's size", 3.0, true};
inline constexpr PhysicalRange length{"a length", "m", 1e-6, 1e3, "a rig's size", 3.0};
inline constexpr PhysicalRange section_dimension{"a section dimension", "m", 1e-5, 10.0, "a frame member", 0.2};
inline constexpr PhysicalRange shell_thickness{"a shell thickness", "m", 1e-5, 10.0, "a frame plate", 0.01};
inline constexpr PhysicalRange area{"an area", "m^2", 1e-10, 100.0, "a frame member", 5e-3};
inline constexpr PhysicalRange second_moment{"a second moment of area", "m^4", 1e-20, 1e3, "a frame member", 3e-5};
inline constexpr PhysicalRange mass{"a mass", "kg", 1e-6, 1e7, "a vehicle", 2000.0};
inline constexpr PhysicalRange point_mass{"a point mass", "kg", 0.0, 1e7, "a vehicle", 2000.0, true};
inline constexpr PhysicalRange inertia{"a moment or product of inertia", "kg m^2", 0.0, 1e9, "a vehicle", 1000.0, true};
inline constexpr PhysicalRange gravity{"gravity", "m/s^2", 1.0, 30.0, "the Earth's", 9.80665};
inline constexpr PhysicalRange sample_rate{"a sample rate", "Hz", 1.0, 1e5, "a rig's data logger", 500.0};
}  // namespace ranges

}  // namespace rigflex::io
