#pragma once
// Global stiffness and mass of a model on its free DOFs: supports removed,
// rigid-coupling dependents eliminated exactly through a transformation.
#include <Eigen/Sparse>
#include <functional>
#include <string>
#include <vector>

#include "fe/dof.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor>;

// Maps between the model's nodal DOFs and the columns of the reduced system.
struct DofMap {
  // For each free column: the node and its local DOF (0..5, fe/dof.hpp).
  std::vector<NodeId> node;
  std::vector<int> local;
  // full_to_free[node_index * 6 + d] = free column, or -1 if fixed,
  // dependent (coupled) or unused (no stiffness and no mass anywhere).
  std::vector<long> full_to_free;
  // Full DOFs (node_index*6+d) -> free DOFs; dependent DOFs are rows of the
  // rigid-coupling transformation, fixed and unused ones are zero rows.
  SpMat T;

  Eigen::Index free_count() const { return static_cast<Eigen::Index>(node.size()); }
  // "node 12 RZ" for a free column.
  std::string describe(Eigen::Index free_dof) const;
  // Expands a free-DOF vector to all nodal DOFs (6 per node, in node order).
  Eigen::VectorXd expand(const Eigen::VectorXd& free) const { return T * free; }
};

struct AssembledSystem {
  SpMat K;  // free DOFs, symmetric, both triangles stored
  SpMat M;
  DofMap dofs;
};

struct AssemblyOptions {
  // Drop DOFs that nothing stiffens and nothing loads with mass (for example
  // the rotations of a node that only springs or point masses touch).
  bool drop_unused_dofs = true;
  // Optional: called with the elements assembled so far and their total at
  // every 2 % of them, the last at the last element (long work shows progress).
  std::function<void(long done, long total)> progress;
};

// Full, unconstrained matrices over all nodal DOFs (6 per node, node order).
void assemble_full(const Model& model, SpMat& K, SpMat& M);
// Validates the model, assembles, and applies supports and couplings.
AssembledSystem assemble(const Model& model, const AssemblyOptions& options = {});

}  // namespace rigflex::fe
