#include "verification/plate_ritz.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rigflex::verification {
namespace {

// Gauss-Legendre nodes and weights on [-1, 1] (Golub-Welsch): exact for
// polynomials up to degree 2n - 1. fe/gauss_legendre.hpp tabulates the
// elements' rules, n <= 4; the series here needs n = terms + 2.
void gauss_legendre(int n, Eigen::VectorXd& x, Eigen::VectorXd& w) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) T(k, k - 1) = T(k - 1, k) = k / std::sqrt(4.0 * k * k - 1.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T);
  x = es.eigenvalues();
  w = 2.0 * es.eigenvectors().row(0).transpose().array().square();
}

// Rows i < n: f_i = (1 - s^2) P_i(s) and f_i' at the nodes s (columns).
// (1 - s^2) P_i' = i (P_{i-1} - s P_i) avoids dividing at the ends.
void bubble_legendre(const Eigen::VectorXd& s, int n, Eigen::MatrixXd& f, Eigen::MatrixXd& df) {
  f.resize(n, s.size());
  df.resize(n, s.size());
  for (Eigen::Index q = 0; q < s.size(); ++q) {
    const double x = s(q);
    double previous = 0.0, p = 1.0;  // P_{i-1}, P_i
    for (int i = 0; i < n; ++i) {
      f(i, q) = (1.0 - x * x) * p;
      df(i, q) = -2.0 * x * p + i * (previous - x * p);
      const double next = ((2.0 * i + 1.0) * x * p - i * previous) / (i + 1.0);
      previous = p;
      p = next;
    }
  }
}

// (A kron B)((i n + j), (k n + l)) = A(i, k) B(j, l): the integral over the
// square of a product of separable functions, i and k along s, j and l along t.
Eigen::MatrixXd kron(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::Index n = B.rows();
  Eigen::MatrixXd K(A.rows() * n, A.cols() * n);
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index k = 0; k < A.cols(); ++k) K.block(i * n, k * n, n, n) = A(i, k) * B;
  return K;
}

}  // namespace

std::vector<double> clamped_plate_frequencies_hz(const ParallelogramPlate& p, int count, int terms) {
  if (!(p.side_a > 0 && p.side_b > 0 && p.thickness > 0 && p.E > 0 && p.rho > 0 && p.nu > -1 && p.nu < 0.5 &&
        p.angle > 0 && p.angle < std::numbers::pi)) {
    throw std::invalid_argument("clamped_plate_frequencies_hz: not a plate");
  }
  const int n = terms, nb = n * n;
  if (n < 1 || count < 1 || count > 3 * nb) throw std::invalid_argument("clamped_plate_frequencies_hz: count or terms");
  // x = a/2 (s + 1) + b/2 (t + 1) cos(angle), y = b/2 (t + 1) sin(angle).
  Eigen::Matrix2d J;
  J << p.side_a / 2, p.side_b / 2 * std::cos(p.angle), 0.0, p.side_b / 2 * std::sin(p.angle);
  const double area = J.determinant();
  const Eigen::Matrix2d A = J.inverse();  // A(k, l) = d s_k / d x_l
  // The integrands are of degree <= 2 (n + 1) along each axis.
  Eigen::VectorXd s, w;
  gauss_legendre(n + 2, s, w);
  Eigen::MatrixXd f, df;
  bubble_legendre(s, n, f, df);
  const Eigen::MatrixXd P0 = f * w.asDiagonal() * f.transpose();    // int f_i f_k
  const Eigen::MatrixXd P1 = df * w.asDiagonal() * f.transpose();   // int f_i' f_k
  const Eigen::MatrixXd P2 = df * w.asDiagonal() * df.transpose();  // int f_i' f_k'
  // Integrals over the plate of products of W (a basis function), Ws, Wt
  // (its derivatives along s and t) and Wx, Wy.
  const Eigen::MatrixXd WW = area * kron(P0, P0), SS = area * kron(P2, P0), TT = area * kron(P0, P2);
  const Eigen::MatrixXd ST = area * kron(P1, P1.transpose()), SW = area * kron(P1, P0), TW = area * kron(P0, P1);
  const Eigen::MatrixXd TS = ST.transpose();
  const Eigen::MatrixXd XX = A(0, 0) * A(0, 0) * SS + A(0, 0) * A(1, 0) * (ST + TS) + A(1, 0) * A(1, 0) * TT;
  const Eigen::MatrixXd YY = A(0, 1) * A(0, 1) * SS + A(0, 1) * A(1, 1) * (ST + TS) + A(1, 1) * A(1, 1) * TT;
  const Eigen::MatrixXd XY =
      A(0, 0) * A(0, 1) * SS + A(0, 0) * A(1, 1) * ST + A(1, 0) * A(0, 1) * TS + A(1, 0) * A(1, 1) * TT;
  const Eigen::MatrixXd XW = A(0, 0) * SW + A(1, 0) * TW, YW = A(0, 1) * SW + A(1, 1) * TW;

  const double t = p.thickness, nu = p.nu;
  const double D = p.E * t * t * t / (12.0 * (1.0 - nu * nu));
  const double S = 5.0 / 6.0 * p.E / (2.0 * (1.0 + nu)) * t;
  // Unknowns [w, phi_x, phi_y]: curvatures (phi_x,x, phi_y,y, phi_x,y + phi_y,x),
  // shear strains (w,x - phi_x, w,y - phi_y).
  Eigen::MatrixXd K(3 * nb, 3 * nb), M = Eigen::MatrixXd::Zero(3 * nb, 3 * nb);
  K.block(0, 0, nb, nb) = S * (XX + YY);
  K.block(0, nb, nb, nb) = -S * XW;
  K.block(0, 2 * nb, nb, nb) = -S * YW;
  K.block(nb, nb, nb, nb) = D * (XX + (1.0 - nu) / 2.0 * YY) + S * WW;
  K.block(nb, 2 * nb, nb, nb) = D * (nu * XY + (1.0 - nu) / 2.0 * XY.transpose());
  K.block(2 * nb, 2 * nb, nb, nb) = D * (YY + (1.0 - nu) / 2.0 * XX) + S * WW;
  K.block(nb, 0, nb, nb) = K.block(0, nb, nb, nb).transpose();
  K.block(2 * nb, 0, nb, nb) = K.block(0, 2 * nb, nb, nb).transpose();
  K.block(2 * nb, nb, nb, nb) = K.block(nb, 2 * nb, nb, nb).transpose();
  M.block(0, 0, nb, nb) = p.rho * t * WW;
  M.block(nb, nb, nb, nb) = M.block(2 * nb, 2 * nb, nb, nb) = p.rho * t * t * t / 12.0 * WW;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) throw std::runtime_error("clamped_plate_frequencies_hz: eigen solver failed");
  std::vector<double> hz;
  for (int k = 0; k < count; ++k) hz.push_back(std::sqrt(std::max(es.eigenvalues()(k), 0.0)) / (2 * std::numbers::pi));
  return hz;
}

}  // namespace rigflex::verification
