#include "reduction/rayleigh_damping.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rigflex::reduction {

RayleighDamping rayleigh_coefficients(const std::array<int, 2>& modes, const std::array<double, 2>& omega,
                                      const std::array<double, 2>& zeta) {
  for (int k = 0; k < 2; ++k) {
    if (!(omega[k] > 0) || !std::isfinite(omega[k])) {
      throw std::invalid_argument("Rayleigh damping: mode " + std::to_string(modes[k]) +
                                  " has no positive frequency (a rigid-body mode cannot set the damping)");
    }
    if (!(zeta[k] > 0 && zeta[k] < 1)) {
      throw std::invalid_argument("zeta: the damping ratio must lie in (0, 1), got " + std::to_string(zeta[k]));
    }
  }
  if (std::abs(omega[0] - omega[1]) <= 1e-9 * std::max(omega[0], omega[1])) {
    throw std::invalid_argument("zeta modes: modes " + std::to_string(modes[0]) + " and " + std::to_string(modes[1]) +
                                " have the same frequency; Rayleigh damping needs two distinct frequencies");
  }
  // [1/(2 w1)  w1/2] [alpha]   [z1]
  // [1/(2 w2)  w2/2] [beta ] = [z2], solved in closed form.
  const double w1 = omega[0], w2 = omega[1];
  RayleighDamping d;
  d.modes = modes;
  d.omega = omega;
  d.zeta = zeta;
  d.alpha = 2 * w1 * w2 * (zeta[0] * w2 - zeta[1] * w1) / (w2 * w2 - w1 * w1);
  d.beta = 2 * (zeta[1] * w2 - zeta[0] * w1) / (w2 * w2 - w1 * w1);
  return d;
}

double rayleigh_ratio(const RayleighDamping& d, double omega) { return d.alpha / (2 * omega) + d.beta * omega / 2; }

Eigen::MatrixXd rayleigh_damping_matrix(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const RayleighDamping& d,
                                        const Eigen::MatrixXd& rigid) {
  Eigen::MatrixXd Me = M;
  if (rigid.size() > 0) {
    const Eigen::MatrixXd MR = M * rigid;
    const Eigen::MatrixXd RMR = rigid.transpose() * MR;
    Me -= MR * RMR.ldlt().solve(MR.transpose());
  }
  Eigen::MatrixXd C = d.alpha * Me + d.beta * K;
  return 0.5 * (C + C.transpose());
}

}  // namespace rigflex::reduction
