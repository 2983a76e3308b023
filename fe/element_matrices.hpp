#pragma once
#include <Eigen/Dense>

namespace rigflex::fe {

// Dense element matrices in global axes, DOFs ordered node by node
// [UX UY UZ RX RY RZ] (fe/dof.hpp), in the element's node order; solids'
// nodes carry [UX UY UZ] only (fe/solid_element.hpp).
struct ElementMatrices {
  Eigen::MatrixXd K;
  Eigen::MatrixXd M;
};

}  // namespace rigflex::fe
