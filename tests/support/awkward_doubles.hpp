#pragma once
// Test data for the writers' round trips.
#include <Eigen/Core>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>

#include "fe/mass_properties.hpp"
#include "fe/model.hpp"

namespace rigflex::test {

// Doubles that break lossy formatting: random bit patterns (any exponent,
// subnormals included), wide-range decimals, and hand-picked values.
class AwkwardDoubles {
 public:
  double next() {
    static const double special[] = {1.0 / 3,
                                     -0.0,
                                     1e-300,
                                     std::numeric_limits<double>::denorm_min(),
                                     std::numeric_limits<double>::min(),
                                     std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::lowest(),
                                     0.1,
                                     2.0 / 3,
                                     -1e300};
    switch (rng_() % 4) {
      case 0:
        for (;;) {
          const double v = std::bit_cast<double>(static_cast<std::uint64_t>(rng_()));
          if (std::isfinite(v)) return v;
        }
      case 1: {
        const double mantissa = std::uniform_real_distribution<double>(-1, 1)(rng_);
        return mantissa * std::pow(10.0, std::uniform_int_distribution<int>(-300, 300)(rng_));
      }
      case 2:
        return std::uniform_real_distribution<double>(-1e3, 1e3)(rng_);
      default:
        return special[rng_() % std::size(special)];
    }
  }
  Eigen::MatrixXd matrix(Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd A(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j)
      for (Eigen::Index i = 0; i < rows; ++i) A(i, j) = next();
    return A;
  }
  Eigen::VectorXd vector(Eigen::Index n) { return matrix(n, 1); }
  fe::Vec3 vec3() { return vector(3); }
  fe::MassProperties mass() {
    fe::MassProperties p;
    p.mass = next();
    p.cog = vec3();
    // The record holds the six entries of a symmetric tensor.
    p.inertia = matrix(3, 3);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < i; ++j) p.inertia(i, j) = p.inertia(j, i);
    return p;
  }

 private:
  std::mt19937_64 rng_{20240611};
};

}  // namespace rigflex::test
