#pragma once
// Savitzky-Golay filters: value, first and second derivative at the centre of
// a least-squares polynomial fit over a sliding window of equally spaced
// samples. They differentiate measured positions without the noise blow-up of
// finite differences, at the price of a bias that grows with frequency.
//
// Bias of the second derivative for a sinusoid of angular frequency w, even
// degree p: the kernels are exact up to degree p+1, so the error starts with
// the term in t^(p+2); in the continuum limit
//   gain - 1 ~ -(-1)^(p/2) (w T)^p P''_{p+2}(0) / (c_{p+2} (p+2)!),
// i.e. -(w T)^4 / 792 for p = 4 and -(w T)^6 / 102960 for p = 6, with
// T = (2m+1) h / 2 (each sample stands for an interval h), P_q the Legendre
// polynomial and c_q its leading coefficient. The next term has the opposite
// sign, so this bounds |gain - 1| from above. At h = 1/500 s, 0.2 s and
// degree 4 (T = 0.101 s) give -3.1e-3 at 2 Hz; the default, 0.3 s and
// degree 6, gives -4.2e-4 with 18 % less noise (docs/identification.md).
#include <Eigen/Core>

namespace rigflex::identify {

struct SavitzkyGolayOptions {
  double window_s = 0.3;  // full window length (s); the half width in samples is round(window_s / (2 h))
  int degree = 6;         // polynomial degree, 2..10
  void validate() const;  // std::invalid_argument naming the field ("differentiation.window_s ...")
};

// Weights of the least-squares polynomial fit over 2*half_width+1 equally spaced samples (spacing h),
// evaluated at the centre: value, first and second derivative. Estimate = sum_k w[k] * x[i - half_width + k].
struct SavitzkyGolayKernels {
  int half_width = 0;
  double h = 0;
  Eigen::VectorXd value, first, second;
};

// std::invalid_argument if 2*half_width+1 <= degree, degree < 2, h <= 0.
SavitzkyGolayKernels savitzky_golay_kernels(int half_width, int degree, double h);
// Kernels for a sample interval h from the options (half width from window_s; at least what the degree needs).
SavitzkyGolayKernels savitzky_golay_kernels(const SavitzkyGolayOptions& options, double h);

// Gain of the estimate of derivative `derivative` (0, 1, 2) for a sinusoid of frequency f_hz, relative to
// the exact derivative (1 = unbiased): for the symmetric kernels this is a real number.
double savitzky_golay_gain(const SavitzkyGolayKernels& k, int derivative, double f_hz);
// Standard deviation of the estimate for white noise of standard deviation 1: sqrt(sum w^2).
double savitzky_golay_noise_gain(const SavitzkyGolayKernels& k, int derivative);

// The three estimates at the sample x[0] of a contiguous signal (x[-m] ..
// x[m] must exist). The value and second-derivative kernels are even and the
// first-derivative kernel odd, so the window is folded once into sums and
// differences of mirrored samples: half the multiplications of three dot
// products, in one pass (the identifier evaluates this per channel at every
// equation time).
struct SavitzkyGolayEstimate {
  double value = 0, first = 0, second = 0;
};
inline SavitzkyGolayEstimate savitzky_golay_at(const SavitzkyGolayKernels& k, const double* x) {
  const int m = k.half_width;
  const double* w0 = k.value.data() + m;
  const double* w1 = k.first.data() + m;
  const double* w2 = k.second.data() + m;
  SavitzkyGolayEstimate e{w0[0] * x[0], 0.0, w2[0] * x[0]};
  for (int j = 1; j <= m; ++j) {
    const double sum = x[j] + x[-j], diff = x[j] - x[-j];
    e.value += w0[j] * sum;
    e.first += w1[j] * diff;
    e.second += w2[j] * sum;
  }
  return e;
}

// The value alone (smoothing).
inline double savitzky_golay_value_at(const SavitzkyGolayKernels& k, const double* x) {
  const int m = k.half_width;
  const double* w0 = k.value.data() + m;
  double v = w0[0] * x[0];
  for (int j = 1; j <= m; ++j) v += w0[j] * (x[j] + x[-j]);
  return v;
}

}  // namespace rigflex::identify
