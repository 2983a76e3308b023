#include "fe/material.hpp"

#include <cmath>

#include "fe/error.hpp"

namespace rigflex::fe {

void Material::validate() const {
  auto fail = [&](const std::string& key, const std::string& why) {
    throw ModelError({"material", name, key}, "material '" + name + "': " + why);
  };
  if (!(std::isfinite(E) && E > 0.0)) fail("E", "E must be positive");
  if (!(std::isfinite(nu) && nu > -1.0 && nu < 0.5)) fail("nu", "nu must lie in (-1, 0.5)");
  if (!(std::isfinite(rho) && rho > 0.0)) fail("rho", "rho must be positive (use mass: none on an element for a massless member)");
}

}  // namespace rigflex::fe
