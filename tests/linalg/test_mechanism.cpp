#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "linalg/mechanism.hpp"
#include "test_pencils.hpp"

namespace rigflex::linalg {
namespace {

using Eigen::Index;
using Eigen::VectorXd;

std::vector<Index> range(Index first, Index last) {
  std::vector<Index> v(static_cast<size_t>(last - first));
  std::iota(v.begin(), v.end(), first);
  return v;
}

// SPD matrix with DOF 5 isolated (zero row) and DOFs 150, 151 coupled only
// to each other by a spring: null vectors e_5 and (e_150 + e_151) / sqrt 2.
SpMat matrix_with_zero_row_and_hinge() {
  SpMat A = testing::random_spd(200, 19);
  A.prune([](Index i, Index j, double) {
    const auto isolated = [](Index d) { return d == 5 || d == 150 || d == 151; };
    return !isolated(i) && !isolated(j);
  });
  A.coeffRef(150, 150) = 2.0;
  A.coeffRef(151, 151) = 2.0;
  A.coeffRef(150, 151) = -2.0;
  A.coeffRef(151, 150) = -2.0;
  A.makeCompressed();
  return A;
}

TEST(Mechanism, ZeroRowAndHingeOfASemidefiniteMatrix) {
  EXPECT_EQ(mechanism_dofs(matrix_with_zero_row_and_hinge()), (std::vector<Index>{5, 150, 151}));
}

TEST(Mechanism, NonsingularMatrixHasNone) {
  EXPECT_TRUE(mechanism_dofs(testing::random_spd(300, 23)).empty());
}

TEST(Mechanism, MasslessFreeSubchainOfAPencil) {
  // Springs 0-1-2-3-4 and 5-6-7-8-9 (two free bodies); mass on 0..4 only.
  // Both bodies have a rigid translation; only the massless one is a
  // mechanism of the pencil.
  testing::Pencil p = testing::spring_chain(10, 1e6, 1.0, true);
  p.K.coeffRef(4, 4) = 1e6;
  p.K.coeffRef(5, 5) = 1e6;
  p.K.coeffRef(4, 5) = 0.0;
  p.K.coeffRef(5, 4) = 0.0;
  for (Index i = 5; i < 10; ++i) p.M.coeffRef(i, i) = 0.0;
  EXPECT_EQ(mechanism_dofs(p.K, p.M), range(5, 10));
  // Scaling K and M changes nothing.
  EXPECT_EQ(mechanism_dofs(SpMat(1e9 * p.K), SpMat(1e-3 * p.M)), range(5, 10));
}

TEST(Mechanism, RigidBodyModesWithMassAreNotAMechanism) {
  const testing::Pencil p = testing::free_lattice(4, 3, 3);
  EXPECT_TRUE(mechanism_dofs(p.K, p.M).empty());
  // K alone is singular along the six rigid-body modes, which move every DOF.
  EXPECT_EQ(mechanism_dofs(p.K), range(0, p.K.rows()));
}

TEST(Mechanism, InvalidSizesThrow) {
  EXPECT_THROW(mechanism_dofs(SpMat(3, 4)), std::invalid_argument);
  EXPECT_THROW(mechanism_dofs(SpMat(3, 3), SpMat(4, 4)), std::invalid_argument);
}

}  // namespace
}  // namespace rigflex::linalg
