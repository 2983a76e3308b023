#include "diagnose/band_noise.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <mutex>
#include <numbers>
#include <vector>

#include "diagnose/fftw_planner.hpp"

namespace rigflex::diagnose {
namespace {

int next_power_of_two(double n) {
  int p = 1;
  while (p < n) p *= 2;
  return p;
}

// One real transform of length n and its inverse on owned buffers, the
// plans made and destroyed under the planner's lock.
class RealTransform {
 public:
  explicit RealTransform(int n)
      : n_(n), real_(fftw_alloc_real(static_cast<size_t>(n))), spectrum_(fftw_alloc_complex(bins())) {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    forward_ = fftw_plan_dft_r2c_1d(n, real_, spectrum_, FFTW_ESTIMATE);
    inverse_ = fftw_plan_dft_c2r_1d(n, spectrum_, real_, FFTW_ESTIMATE);
  }
  ~RealTransform() {
    {
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      fftw_destroy_plan(forward_);
      fftw_destroy_plan(inverse_);
    }
    fftw_free(spectrum_);
    fftw_free(real_);
  }
  RealTransform(const RealTransform&) = delete;
  RealTransform& operator=(const RealTransform&) = delete;

  size_t bins() const { return static_cast<size_t>(n_ / 2 + 1); }
  double* real() { return real_; }
  std::complex<double> bin(size_t k) const { return {spectrum_[k][0], spectrum_[k][1]}; }
  void set_bin(size_t k, std::complex<double> v) {
    spectrum_[k][0] = v.real();
    spectrum_[k][1] = v.imag();
  }
  void forward() { fftw_execute(forward_); }
  void inverse() { fftw_execute(inverse_); }  // unnormalized: n x the signal

 private:
  int n_;
  double* real_;
  fftw_complex* spectrum_;
  fftw_plan forward_, inverse_;
};

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
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

  RealTransform segment(n);
  Eigen::VectorXd window(n);
  for (int k = 0; k < n; ++k) window(k) = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * k / n);
  const double window_power = window.squaredNorm();
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
    Eigen::VectorXd power = Eigen::VectorXd::Zero(last_bin - first_bin + 1);
    int segments = 0;
    for (Eigen::Index start = 0; start + n <= interior; start += n / 2, ++segments) {
      for (int k = 0; k < n; ++k) segment.real()[k] = high(start + k) * window(k);
      segment.forward();
      for (int k = first_bin; k <= last_bin; ++k)
        power(k - first_bin) += std::norm(segment.bin(static_cast<size_t>(k)));
    }
    const double dof = 2.0 * segments, median_of_mean = std::pow(1.0 - 2.0 / (9.0 * dof), 3);
    sigma(c) = std::sqrt(median(std::vector<double>(power.data(), power.data() + power.size())) /
                         (segments * window_power * median_of_mean));
  }
  return sigma;
}

Eigen::VectorXd band_noise(const Eigen::VectorXd& white, const Eigen::VectorXd& near_band) {
  if (near_band.size() != white.size()) return white;
  return white.cwiseMax(near_band / kColouredNoiseMargin);
}

}  // namespace rigflex::diagnose
