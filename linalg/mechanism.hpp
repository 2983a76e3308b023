#pragma once
// Mechanism diagnosis: which DOFs move in the null space of a singular
// pencil, so that a caller can name them ("node 12 RZ, node 13 RZ").
#include <Eigen/Core>
#include <vector>

#include "linalg/sparse_cholesky.hpp"

namespace rigflex::linalg {

// Relative pivots (pivot / A_kk) below this are treated as numerically zero
// at the default shift: rounding puts a mechanism's pivot at ~1e-16..1e-14,
// while a rigid-body pivot there is ~1e-10 times (rigid-body mass) / M_kk.
inline constexpr double kTinyPivot = 1e-13;

// DOFs that move in null(A) for a symmetric positive SEMIdefinite A: those
// whose row of A is exactly zero, and those whose component in an
// orthonormal basis of the numerical null space exceeds 5 % of the largest.
// "Numerical null space": directions with Rayleigh quotient below 1e-10 of
// the (unit) diagonal of D^-1/2 A D^-1/2, D = diag(A). Sorted ascending;
// empty if A is nonsingular. Directions that are merely soft (e.g. the
// rigid-body modes of K - sigma M for a tiny sigma) can fall below that
// threshold: prefer the (K, M) overload for pencils.
std::vector<Eigen::Index> mechanism_dofs(const SpMat& A);

// DOFs moving in null(K) ∩ null(M): motions with neither stiffness nor mass,
// which make K - sigma M singular for every sigma. Computed as null(K + s M),
// s = sum(K_ii)/sum(M_ii) over massed DOFs, where rigid-body modes are far
// from singular (their Rayleigh quotient is s times their mass).
std::vector<Eigen::Index> mechanism_dofs(const SpMat& K, const SpMat& M);

}  // namespace rigflex::linalg
