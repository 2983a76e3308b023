#include "diagnose/swing_band.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rig/median.hpp"

namespace rigflex::diagnose {

SwingBand swing_band(double step_s, double highest_swing_hz) {
  if (!(step_s > 0)) throw std::invalid_argument("sample interval must be positive");
  if (!(highest_swing_hz > 0)) throw std::invalid_argument("the rig model has no swing mode");
  SwingBand b;
  b.step_s = step_s;
  b.swing_hz = highest_swing_hz;
  const double fs = 1.0 / step_s;
  // Pass up to 1.25 x the highest swing mode, stop from 3 x (where a rig
  // that meets the 3-4x design rule has its first deformation mode).
  const double pass = 1.25 * highest_swing_hz, stop = std::min(3.0 * highest_swing_hz, 0.4 * fs);
  if (!(stop > pass)) {
    throw std::invalid_argument("a sample rate of " + std::to_string(fs) + " Hz is too low for the swing band (needs > " +
                                std::to_string(3.2 * highest_swing_hz) + " Hz)");
  }
  b.cutoff_hz = 0.5 * (pass + stop);
  const double transition = stop - pass;
  // Kaiser window for 60 dB in the stop band (Kaiser's formulas).
  const double attenuation = 60.0, beta = 0.1102 * (attenuation - 8.7);
  const int taps = static_cast<int>(std::ceil((attenuation - 8.0) / (2.285 * 2.0 * std::numbers::pi * transition / fs)));
  const int m = std::max(2, taps / 2);
  b.kernel.resize(2 * m + 1);
  const double wc = 2.0 * std::numbers::pi * b.cutoff_hz * step_s;
  const double i0_beta = std::cyl_bessel_i(0.0, beta);
  for (int k = -m; k <= m; ++k) {
    const double x = static_cast<double>(k);
    const double sinc = k == 0 ? wc / std::numbers::pi : std::sin(wc * x) / (std::numbers::pi * x);
    const double r = x / m;
    const double w = std::cyl_bessel_i(0.0, beta * std::sqrt(std::max(0.0, 1.0 - r * r))) / i0_beta;
    b.kernel(k + m) = sinc * w;
  }
  b.kernel /= b.kernel.sum();
  b.decimation = std::max(1, static_cast<int>(std::floor(fs / (4.0 * b.cutoff_hz))));
  return b;
}

std::vector<Eigen::Index> band_samples(const SwingBand& b, Eigen::Index samples, Eigen::Index first,
                                       Eigen::Index last) {
  const Eigen::Index m = b.half_width();
  if (last < 0 || last > samples - 1 - m) last = samples - 1 - m;
  std::vector<Eigen::Index> at;
  for (Eigen::Index k = std::max(first, m); k <= last; k += b.decimation) at.push_back(k);
  return at;
}

Eigen::MatrixXd band_filter(const SwingBand& b, const Eigen::MatrixXd& channels, const std::vector<Eigen::Index>& at) {
  const Eigen::Index m = b.half_width();
  Eigen::MatrixXd out(static_cast<Eigen::Index>(at.size()), channels.cols());
  for (Eigen::Index c = 0; c < channels.cols(); ++c) {
    const double* x = channels.col(c).data();
    for (size_t r = 0; r < at.size(); ++r) {
      const double* w = x + at[r] - m;
      double s = 0;
      for (Eigen::Index k = 0; k < b.kernel.size(); ++k) s += b.kernel(k) * w[k];
      out(static_cast<Eigen::Index>(r), c) = s;
    }
  }
  return out;
}

UniformRecord uniform_record(const Eigen::VectorXd& t, const Eigen::MatrixXd& channels) {
  if (t.size() < 4) throw std::invalid_argument("a record needs at least four samples");
  UniformRecord u;
  u.step_s = rig::median_step(t);
  if (!(u.step_s > 0)) throw std::invalid_argument("time must increase");
  const Eigen::Index n = static_cast<Eigen::Index>(std::floor((t(t.size() - 1) - t(0)) / u.step_s + 1e-6)) + 1;
  u.t = Eigen::VectorXd::LinSpaced(n, t(0), t(0) + static_cast<double>(n - 1) * u.step_s);
  u.channels.resize(n, channels.cols());
  Eigen::Index j = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double tk = u.t(k);
    while (j + 2 < t.size() && t(j + 1) <= tk) ++j;
    const double span = t(j + 1) - t(j);
    const double a = std::clamp((tk - t(j)) / span, 0.0, 1.0);
    u.channels.row(k) = (1.0 - a) * channels.row(j) + a * channels.row(j + 1);
  }
  return u;
}

}  // namespace rigflex::diagnose
