#pragma once
// Gauss-Legendre points and weights on [-1, 1], from which the shells'
// square rules and the solids' cube and tetrahedron rules are built.
#include <vector>

namespace rigflex::fe {

struct GaussLegendre {
  std::vector<double> x, w;
};

// n = 1..4 points, exact for polynomials of degree 2n - 1; throws
// std::invalid_argument for any other n.
GaussLegendre gauss_legendre(int n);

}  // namespace rigflex::fe
