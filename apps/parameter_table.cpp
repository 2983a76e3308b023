#include "apps/parameter_table.hpp"

#include <algorithm>
#include <cstdio>

namespace rigflex::app {

std::string fitted_parameters_label(const std::vector<diagnose::FittedParameter>& ps) {
  const bool rods = std::any_of(ps.begin(), ps.end(), [](const auto& p) { return p.name == "rods.stiffness"; });
  const bool effects =
      std::any_of(ps.begin(), ps.end(), [](const auto& p) { return p.name.rfind("effects.", 0) == 0; });
  std::string label = "body";
  if (rods) label += " and rods' stiffness";
  if (effects) label += " and effects' values";
  return label;
}

void print_parameter_table(const std::vector<diagnose::FittedParameter>& ps) {
  int width = 6;
  for (const auto& p : ps) width = std::max(width, static_cast<int>(p.name.size()));
  for (const auto& p : ps) {
    const double k = p.unit == "m" ? 1e3 : 1.0;
    const char* unit = p.unit == "m" ? "mm" : p.unit.c_str();
    std::printf("  %-*s %+10.4g +- %-9.3g %s (stated %.3g)%s\n", width, p.name.c_str(), k * p.value, k * p.std, unit,
                k * p.prior_std, p.off ? "  OFF" : "");
  }
}

}  // namespace rigflex::app
