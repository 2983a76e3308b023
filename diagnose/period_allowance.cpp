#include "diagnose/period_allowance.hpp"

#include <stdexcept>

namespace rigflex::diagnose {
namespace {

// d/dt of the band-filtered channels at the band samples: a one-sided
// difference of the filter at a neighbouring raw sample against the
// measured band samples (its error, omega h / 2, is below 1 % for swings
// under 1.6 Hz at 500 Hz) - forward, or backward where the kernel would
// run past the record's end.
Eigen::MatrixXd band_rate(const BandTarget& b) {
  const Eigen::Index samples = b.record.t.size(), m = b.band.half_width();
  std::vector<Eigen::Index> neighbour(b.at);
  Eigen::VectorXd direction(static_cast<Eigen::Index>(b.at.size()));
  for (size_t k = 0; k < b.at.size(); ++k) {
    const bool forward = b.at[k] + 1 + m < samples;
    neighbour[k] = forward ? b.at[k] + 1 : b.at[k] - 1;
    direction(static_cast<Eigen::Index>(k)) = forward ? 1.0 : -1.0;
  }
  return direction.asDiagonal() * (band_filter(b.band, b.record.channels, neighbour) - b.measured) / b.record.step_s;
}

}  // namespace

double period_error_residual(const std::vector<const BandTarget*>& targets, double period_error) {
  if (!(period_error >= 0)) throw std::invalid_argument("period_error_residual: period error must be >= 0");
  if (period_error == 0) return 0;
  double sum = 0;
  for (const BandTarget* b : targets) {
    if (b->at.empty()) continue;
    const Eigen::MatrixXd rate = band_rate(*b) * b->weight.asDiagonal();
    Eigen::MatrixXd drift = rate;
    const double t0 = b->record.t(b->at.front());
    for (size_t k = 0; k < b->at.size(); ++k) {
      drift.row(static_cast<Eigen::Index>(k)) *= period_error * (b->record.t(b->at[k]) - t0);
    }
    const double norm = rate.squaredNorm();
    const double shift = norm > 0 ? (drift.array() * rate.array()).sum() / norm : 0.0;
    sum += (drift - shift * rate).squaredNorm();
  }
  return sum;
}

}  // namespace rigflex::diagnose
