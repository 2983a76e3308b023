#include "io/physical_range.hpp"

#include <cmath>
#include <cstdio>

namespace rigflex::io {
namespace {

std::string g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

}  // namespace

std::string range_problem(double x, const PhysicalRange& r) {
  const double v = r.magnitude ? std::abs(x) : x;
  if (v >= r.lo && v <= r.hi) return "";
  if (r.magnitude && x == 0.0) return "";
  const std::string plausible = "(plausible: " + std::string(r.magnitude ? "|x| " : "") +
                                (r.lo > 0 ? g(r.lo) + " to " : "up to ") + g(r.hi) + " " + r.unit + ")";
  const std::string expected = std::string(r.quantity) + " in " + r.unit + " expected: ";
  if (!(v > 0)) return expected + g(x) + " must be positive " + plausible;
  const double orders = std::log10(v / r.typical);
  const long n = std::lround(std::abs(orders));
  const std::string far = n >= 1 ? std::to_string(n) + (n == 1 ? " order" : " orders") + " of magnitude " +
                                       (orders < 0 ? "below " : "above ")
                                 : std::string(orders < 0 ? "below " : "above ");
  return expected + g(x) + " is " + far + r.typical_name + " (" + g(r.typical) + " " + r.unit + ") - units? " +
         plausible;
}

}  // namespace rigflex::io
