#pragma once
// Point masses and linear springs.
#include "fe/element_matrices.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

// 6x6 mass of a point mass with rotary inertia about its node.
Eigen::Matrix<double, 6, 6> point_mass_matrix(const PointMass& p);

// 6x6 stiffness of a spring seen from one node (the node-node element is
// [[k, -k], [-k, k]] of it). `other_position` is used for axial springs
// between two nodes without an explicit direction.
Eigen::Matrix<double, 6, 6> spring_stiffness(const Spring& s, const Vec3& node_position,
                                             const Vec3& other_position);

}  // namespace rigflex::fe
