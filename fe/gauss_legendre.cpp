#include "fe/gauss_legendre.hpp"

#include <cmath>
#include <stdexcept>

namespace rigflex::fe {

GaussLegendre gauss_legendre(int n) {
  switch (n) {
    case 1:
      return {{0.0}, {2.0}};
    case 2:
      return {{-1 / std::sqrt(3.0), 1 / std::sqrt(3.0)}, {1.0, 1.0}};
    case 3:
      return {{-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, {5 / 9.0, 8 / 9.0, 5 / 9.0}};
    case 4: {
      const double a = std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(1.2)), b = std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(1.2));
      const double wa = (18 + std::sqrt(30.0)) / 36, wb = (18 - std::sqrt(30.0)) / 36;
      return {{-b, -a, a, b}, {wb, wa, wa, wb}};
    }
    default:
      throw std::invalid_argument("gauss_legendre: n must be 1, 2, 3 or 4");
  }
}

}  // namespace rigflex::fe
