#include "diagnose/fit_discrimination.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rigflex::diagnose {

FitDiscrimination discriminate(const DiscriminationInput& in) {
  if (!in.first || !in.second || in.first->size() != in.second->size() || in.first->size() != in.rows.size()) {
    throw std::invalid_argument("discriminate: both fits need a residual per history and its rows");
  }
  if (!(in.independence > 0 && in.independence <= 1)) {
    throw std::invalid_argument("discriminate: independence must lie in (0, 1]");
  }
  double ratio = 0, apart = 0, first = 0, second = 0, samples = 0;
  for (size_t j = 0; j < in.first->size(); ++j) {
    const Eigen::VectorXd& a = (*in.first)[j];
    const Eigen::VectorXd& b = (*in.second)[j];
    if (in.rows[j] <= 0 || a.size() != b.size() || a.size() % in.rows[j] != 0) {
      throw std::invalid_argument("discriminate: history " + std::to_string(j) +
                                  ": residual sizes do not match the band's rows");
    }
    ratio += 0.5 * (b.squaredNorm() - a.squaredNorm());
    apart += (b - a).squaredNorm();
    first += a.squaredNorm();
    second += b.squaredNorm();
    samples += static_cast<double>(a.size());
  }
  FitDiscrimination out;
  const double n = samples * in.independence;
  out.log_likelihood_ratio = ratio;
  out.penalized = ratio - (n > 1 ? 0.5 * in.parameter_difference * std::log(n) : 0.0);
  const double residual = samples > 0 ? std::max(1.0, std::min(first, second) / samples) : 1.0;
  const double variance = residual * apart / in.independence;
  if (!(variance > 0)) {
    out.z = out.log_likelihood_ratio == 0 ? 0.0 : std::copysign(INFINITY, out.log_likelihood_ratio);
    out.p_value = out.log_likelihood_ratio == 0 ? 1.0 : 0.0;
    return out;
  }
  out.z = out.log_likelihood_ratio / std::sqrt(variance);
  const boost::math::normal_distribution<double> n01;
  out.p_value = 2.0 * boost::math::cdf(boost::math::complement(n01, std::abs(out.z)));
  return out;
}

}  // namespace rigflex::diagnose
