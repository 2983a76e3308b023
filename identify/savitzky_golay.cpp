#include "identify/savitzky_golay.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rigflex::identify {

namespace {

// Far beyond any sensible window; keeps 2 * half_width + 1 and the rounded
// window_s / (2 h) inside int.
constexpr int max_half_width = INT_MAX / 4;

const Eigen::VectorXd& kernel(const SavitzkyGolayKernels& k, int derivative) {
  if (derivative < 0 || derivative > 2) {
    throw std::invalid_argument("savitzky_golay: derivative must be 0, 1 or 2, not " + std::to_string(derivative));
  }
  const Eigen::VectorXd& w = derivative == 0 ? k.value : derivative == 1 ? k.first : k.second;
  if (k.half_width < 0 || w.size() != 2 * static_cast<Eigen::Index>(k.half_width) + 1) {
    throw std::invalid_argument("savitzky_golay: kernel size does not match half_width");
  }
  return w;
}

}  // namespace

void SavitzkyGolayOptions::validate() const {
  if (!(window_s > 0 && std::isfinite(window_s))) {
    throw std::invalid_argument("differentiation.window_s must be positive and finite, not " + std::to_string(window_s));
  }
  if (degree < 2 || degree > 10) {
    throw std::invalid_argument("differentiation.degree must be in 2..10, not " + std::to_string(degree));
  }
}

SavitzkyGolayKernels savitzky_golay_kernels(int half_width, int degree, double h) {
  if (degree < 2) throw std::invalid_argument("savitzky_golay_kernels: degree must be at least 2");
  if (!(h > 0 && std::isfinite(h))) throw std::invalid_argument("savitzky_golay_kernels: h must be positive and finite");
  if (2 * static_cast<long long>(half_width) + 1 <= degree) {
    throw std::invalid_argument("savitzky_golay_kernels: half_width " + std::to_string(half_width) +
                                " gives too few samples for degree " + std::to_string(degree));
  }
  if (half_width > max_half_width) throw std::invalid_argument("savitzky_golay_kernels: half_width is too large");
  const int m = half_width, n = 2 * m + 1, cols = degree + 1;
  // Legendre polynomials of t in [-1, 1] are close to orthogonal on the
  // equispaced grid, so the least-squares problem stays well conditioned for
  // long windows and high degrees, where monomials in sample units would not.
  Eigen::MatrixXd P(n, cols);
  for (int k = 0; k < n; ++k) {
    const double t = static_cast<double>(k - m) / m;
    P(k, 0) = 1.0;
    P(k, 1) = t;
    for (int j = 1; j + 1 < cols; ++j) P(k, j + 1) = ((2 * j + 1) * t * P(k, j) - j * P(k, j - 1)) / (j + 1);
  }
  // P_j(0), P_j'(0), P_j''(0): the recurrence differentiated once and twice.
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(cols, 3);
  D(0, 0) = 1.0;
  D(1, 1) = 1.0;
  for (int j = 1; j + 1 < cols; ++j) {
    D(j + 1, 0) = -j * D(j - 1, 0) / (j + 1);
    D(j + 1, 1) = ((2 * j + 1) * D(j, 0) - j * D(j - 1, 1)) / (j + 1);
    D(j + 1, 2) = (2 * (2 * j + 1) * D(j, 1) - j * D(j - 1, 2)) / (j + 1);
  }
  // P = Q R by Gram-Schmidt, each column orthogonalised twice ("twice is
  // enough" for columns this close to orthogonal). Eigen's HouseholderQR
  // would do as well but trips GCC 12's -Wmaybe-uninitialized.
  Eigen::MatrixXd Q = P, R = Eigen::MatrixXd::Zero(cols, cols);
  for (int j = 0; j < cols; ++j) {
    for (int pass = 0; pass < 2; ++pass) {
      for (int i = 0; i < j; ++i) {
        const double r = Q.col(i).dot(Q.col(j));
        Q.col(j) -= r * Q.col(i);
        R(i, j) += r;
      }
    }
    R(j, j) = Q.col(j).norm();
    Q.col(j) /= R(j, j);
  }
  // The fit is c = R^-1 Q^T x, so the weights of D^T c are Q R^-T D.
  const Eigen::MatrixXd W = Q * R.triangularView<Eigen::Upper>().transpose().solve(D);

  // Exact kernels are even (value, second) or odd (first); imposing that
  // removes rounding that would otherwise leak into the opposite phase.
  const Eigen::MatrixXd M = W.colwise().reverse();
  const double scale = 1.0 / (m * h);
  SavitzkyGolayKernels out;
  out.half_width = m;
  out.h = h;
  out.value = 0.5 * (W.col(0) + M.col(0));
  out.first = 0.5 * scale * (W.col(1) - M.col(1));
  out.second = 0.5 * scale * scale * (W.col(2) + M.col(2));
  return out;
}

SavitzkyGolayKernels savitzky_golay_kernels(const SavitzkyGolayOptions& options, double h) {
  options.validate();
  if (!(h > 0 && std::isfinite(h))) throw std::invalid_argument("savitzky_golay_kernels: h must be positive and finite");
  const double half = std::round(options.window_s / (2.0 * h));
  if (!(half <= max_half_width)) {
    throw std::invalid_argument("differentiation.window_s is too long for the sample interval " + std::to_string(h) +
                                " s");
  }
  const int needed = (options.degree + 1) / 2;  // 2 m + 1 > degree
  return savitzky_golay_kernels(std::max(static_cast<int>(half), needed), options.degree, h);
}

double savitzky_golay_gain(const SavitzkyGolayKernels& k, int derivative, double f_hz) {
  const Eigen::VectorXd& w = kernel(k, derivative);
  const double omega = 2.0 * std::numbers::pi * f_hz;
  // The exact derivatives are 1, omega and -omega^2 times the phase factor.
  // The second uses sum w = 0 to write -cos as 2 sin^2(x / 2) - 1: dividing
  // by omega^2 then cancels nothing at low frequency, and f = 0 gives the limit.
  double sum = 0;
  for (int j = -k.half_width; j <= k.half_width; ++j) {
    const double s = j * k.h, wj = w(j + k.half_width);
    if (derivative == 0) {
      sum += wj * std::cos(omega * s);
    } else if (derivative == 1) {
      sum += wj * (omega == 0 ? s : std::sin(omega * s) / omega);
    } else {
      const double half_sin = omega == 0 ? s / 2 : std::sin(omega * s / 2) / omega;
      sum += 2.0 * wj * half_sin * half_sin;
    }
  }
  return sum;
}

double savitzky_golay_noise_gain(const SavitzkyGolayKernels& k, int derivative) { return kernel(k, derivative).norm(); }

}  // namespace rigflex::identify
