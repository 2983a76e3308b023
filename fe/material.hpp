#pragma once
#include <string>

namespace rigflex::fe {

// Linear isotropic elastic material.
struct Material {
  std::string name;
  double E = 0.0;    // Young's modulus [Pa]
  double nu = 0.0;   // Poisson's ratio [-]
  double rho = 0.0;  // density [kg/m^3]

  double G() const { return E / (2.0 * (1.0 + nu)); }
  // Throws ModelError naming the offending key.
  void validate() const;
};

}  // namespace rigflex::fe
