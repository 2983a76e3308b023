#pragma once
// Visits every element of a model with its dense matrices and the full DOF
// indices (node_index * 6 + local DOF) they act on.
#include <functional>
#include <vector>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

using ElementVisitor = std::function<void(const std::vector<long>& full_dofs, const Eigen::MatrixXd& K,
                                          const Eigen::MatrixXd& M)>;

// The model must be valid (Model::validate). Throws ModelError naming the
// element whose matrices are not finite.
void for_each_element(const Model& model, const ElementVisitor& visit);
// How many elements for_each_element visits: beams, shells, solids, point masses, springs, superelements.
long element_count(const Model& model);

// Computes every element's matrices and throws as for_each_element does: for
// readers, which can still name the line that made the element.
void check_element_matrices(const Model& model);

}  // namespace rigflex::fe
