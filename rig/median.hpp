#pragma once
// Medians for robust scales: a noise level from differences, a sample
// step from time stamps with a dropped sample in them.
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace rigflex::rig {

// The upper median (element size/2 in sorted order; no averaging of the
// two middle ones: a robust scale needs no more), 0 for none.
inline double upper_median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The median step of time stamps `t` (0 for fewer than two): the nominal
// sample interval, whatever a logger pause does to the mean.
inline double median_step(const Eigen::VectorXd& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> d(static_cast<std::size_t>(t.size() - 1));
  for (Eigen::Index k = 0; k + 1 < t.size(); ++k) d[static_cast<std::size_t>(k)] = t(k + 1) - t(k);
  return upper_median(std::move(d));
}

}  // namespace rigflex::rig
