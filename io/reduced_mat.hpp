#pragma once
// reduced.mat: a reduced frame for MATLAB, Octave, scipy.io.loadmat and
// Simscape's Reduced Order Flexible Solid. MAT 5 format, uncompressed (the
// matrices are dense and their digits do not compress much), written and
// read with matio. Every variable is a real double matrix:
//   K M C                  n x n, n = m interface DOFs + N modal coordinates
//   A B Css D              the state space; Css is its output matrix (C is
//                          the damping matrix)
//   T                      n x n, its coordinates: z = T xi, x = [xi; xi']
//                          (the identity for physical coordinates)
//   interface_nodes        k x 1 node ids, in the interface set's order
//   interface_coordinates  k x 3, m
//   dof_node dof_index     m x 1: node id and 1..6 (UX UY UZ RX RY RZ) of
//                          each interface DOF, the first m rows of K
//   alpha beta             1 x 1, Rayleigh damping C = alpha M + beta K
//   mode_frequencies_hz    N x 1, the fixed-interface modes kept
#include <Eigen/Core>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "reduction/reduced_model.hpp"

namespace rigflex::io {

struct ReducedMatVariables {
  Eigen::MatrixXd K, M, C, A, B, Css, D, T;
  Eigen::VectorXd interface_nodes;
  Eigen::MatrixXd interface_coordinates;
  Eigen::VectorXd dof_node, dof_index;
  double alpha = 0.0;
  double beta = 0.0;
  Eigen::VectorXd mode_frequencies_hz;
};

// Checks `r` (check_exportable) and copies what reduced.mat holds.
ReducedMatVariables reduced_mat_variables(const reduction::ReducedFrame& r);

// Writes `v` as it is, atomically; only reduced_mat_variables promises
// consistent sizes. std::runtime_error naming the file when matio fails.
void write_reduced_mat(const std::filesystem::path& file, const ReducedMatVariables& v);
// Checks `r` now and adds the file to `batch` (the caller commits).
void add_reduced_mat_file(FileBatch& batch, const std::filesystem::path& file, const reduction::ReducedFrame& r);

// Throws InputError naming the file and the variable: not a MAT file, a
// variable missing or not a real double matrix, sizes that contradict each
// other, a dof_index outside 1..6 or a dof_node that is not an interface node.
// A file without T (rigflex before the state space's coordinates) reads T = I.
ReducedMatVariables read_reduced_mat(const std::filesystem::path& file);

}  // namespace rigflex::io
