#include "diagnose/band_noise.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "diagnose/real_transform.hpp"
#include "diagnose/welch.hpp"
#include "rig/median.hpp"

namespace rigflex::diagnose {
namespace {

int next_power_of_two(double n) {
  int p = 1;
  while (p < n) p *= 2;
  return p;
}

}  // namespace

Eigen::VectorXd near_band_noise(const Eigen::MatrixXd& channels, const SwingBand& band) {
  const double highest_swing_hz = band.swing_hz;
  const Eigen::Index samples = channels.rows(), C = channels.cols();
  Eigen::VectorXd sigma = Eigen::VectorXd::Zero(C);
  const int hw = band.half_width();
  const Eigen::Index interior = samples - 2 * hw;
  const double fs = 1.0 / band.step_s;
  // Bins of at most half the highest swing frequency; the range from 3.5 x
  // it (above the low-pass's stop band, 3 x) to 15 x, below 0.45 fs.
  const int n = next_power_of_two(2.0 * fs / highest_swing_hz);
  const int first_bin = static_cast<int>(std::ceil(3.5 * highest_swing_hz * n / fs));
  const int last_bin = static_cast<int>(std::floor(std::min(15.0 * highest_swing_hz, 0.45 * fs) * n / fs));
  if (interior < n || last_bin - first_bin + 1 < 16) return sigma;

  // The swing taken out: each channel minus its band low-pass, by one
  // transform of the zero-padded record (no wrap-around on the interior).
  const int L = next_power_of_two(static_cast<double>(samples + band.kernel.size()));
  RealTransform whole(L);
  std::vector<std::complex<double>> pass(whole.bins());
  std::fill(whole.real(), whole.real() + L, 0.0);
  for (int j = -hw; j <= hw; ++j) whole.real()[(j + L) % L] = band.kernel(j + hw);  // centred: zero phase
  whole.forward();
  for (size_t k = 0; k < pass.size(); ++k) pass[k] = whole.bin(k);

  Eigen::VectorXd high(interior);
  for (Eigen::Index c = 0; c < C; ++c) {
    std::fill(whole.real(), whole.real() + L, 0.0);
    for (Eigen::Index i = 0; i < samples; ++i) whole.real()[i] = channels(i, c);
    whole.forward();
    for (size_t k = 0; k < pass.size(); ++k) whole.set_bin(k, whole.bin(k) * (1.0 - pass[k]) / static_cast<double>(L));
    whole.inverse();
    for (Eigen::Index i = 0; i < interior; ++i) high(i) = whole.real()[hw + i];
    // Welch's estimate, half-overlapping Hann segments, then its median
    // over the near band's bins: a line (a frame's ringing, a harmonic)
    // raises the few bins of its main lobe and first sidelobes, which the
    // median passes over. A bin of white noise averages K segments' cells
    // (each exponential, mean sigma^2 x the window's power): chi-square with
    // 2K degrees of freedom / 2K, whose median is (1 - 2 / (18 K))^3 of the
    // mean (Wilson and Hilferty).
    const WelchSums w = welch_sums(high, n);
    const Eigen::VectorXd near = w.power.segment(first_bin, last_bin - first_bin + 1);
    const double dof = 2.0 * w.segments, median_of_mean = std::pow(1.0 - 2.0 / (9.0 * dof), 3);
    sigma(c) = std::sqrt(rig::upper_median(std::vector<double>(near.data(), near.data() + near.size())) /
                         (w.segments * w.window_power * median_of_mean));
  }
  return sigma;
}

Eigen::VectorXd band_noise(const Eigen::VectorXd& white, const Eigen::VectorXd& near_band) {
  if (near_band.size() != white.size()) return white;
  return white.cwiseMax(near_band / kColouredNoiseMargin);
}

}  // namespace rigflex::diagnose
