#pragma once
// The kinematics of a distributing coupling (RBE3): the rigid motion that
// fits the nodes' translations best in the weighted least-squares sense,
// evaluated at the reference node.
//
// With W = sum w_i, centroid c = sum w_i x_i / W, r_i = x_i - c and
// S = sum w_i (|r_i|^2 I - r_i r_i'), minimizing
// sum w_i |u_i - u_c - theta x r_i|^2 gives
//   theta = S^-1 sum w_i r_i x u_i,   u_c = sum w_i u_i / W,
// and the reference at x_r moves as u_r = u_c + theta x (x_r - c). A rigid
// motion of the nodes is reproduced exactly; any other motion is averaged,
// never resisted (the coupling's transpose spreads the reference's loads
// and inertia over the nodes: nodal forces of a rigid body's statics).
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "fe/model.hpp"

namespace rigflex::fe {

// [u_r; theta_r] = G [u_1; ...; u_n] (translations of the nodes, in order):
// a 6 x 3n matrix. Empty weights: all 1. std::nullopt when the nodes do not
// fix a rotation (fewer than three, or all on one line): then S is singular
// and the rotation about that line is undefined.
std::optional<Eigen::MatrixXd> distributing_link(const Vec3& reference, const std::vector<Vec3>& nodes,
                                                 const std::vector<double>& weights);

}  // namespace rigflex::fe
