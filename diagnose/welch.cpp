#include "diagnose/welch.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "diagnose/real_transform.hpp"

namespace rigflex::diagnose {

WelchSums welch_sums(const Eigen::VectorXd& x, int n) {
  if (n < 2) throw std::invalid_argument("welch_sums: a segment needs at least 2 samples");
  WelchSums w;
  w.power = Eigen::VectorXd::Zero(n / 2 + 1);
  Eigen::VectorXd window(n);
  for (int k = 0; k < n; ++k) window(k) = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * k / n);
  w.window_power = window.squaredNorm();
  if (x.size() < n) return w;
  RealTransform segment(n);
  for (Eigen::Index start = 0; start + n <= x.size(); start += n / 2, ++w.segments) {
    const double mean = x.segment(start, n).mean();
    for (int k = 0; k < n; ++k) segment.real()[k] = (x(start + k) - mean) * window(k);
    segment.forward();
    for (int k = 0; k <= n / 2; ++k) w.power(k) += std::norm(segment.bin(static_cast<size_t>(k)));
  }
  return w;
}

}  // namespace rigflex::diagnose
