#pragma once
// Rayleigh damping C = alpha M + beta K from the damping ratio at two modes.
#include <Eigen/Core>
#include <array>

#include "reduction/reduced_model.hpp"

namespace rigflex::reduction {

// alpha and beta such that zeta(omega[k]) = zeta[k], where
// zeta(omega) = alpha / (2 omega) + beta omega / 2. Throws
// std::invalid_argument if an omega is not positive, the two coincide
// (relative 1e-9: the 2x2 system is then singular), or a zeta lies outside
// (0, 1).
RayleighDamping rayleigh_coefficients(const std::array<int, 2>& modes, const std::array<double, 2>& omega,
                                      const std::array<double, 2>& zeta);

// The damping ratio Rayleigh damping gives a mode of circular frequency omega > 0.
double rayleigh_ratio(const RayleighDamping& d, double omega);

// C = alpha M_e + beta K. M_e = M - M R (R' M R)^-1 R' M when `rigid`
// (columns: the rigid-body motions in the same coordinates) is not empty, so
// that rigid-body motion is not damped; M_e = M otherwise.
Eigen::MatrixXd rayleigh_damping_matrix(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const RayleighDamping& d,
                                        const Eigen::MatrixXd& rigid);

}  // namespace rigflex::reduction
