// The solid elements (hex8 with incompatible modes, hex20, tet10) against
// exact properties of elasticity:
//  * null space: exactly the six rigid-body motions on a distorted element
//    (a seventh zero eigenvalue would be a spurious mode);
//  * patch test: on a mesh whose interior nodes are moved off the regular
//    grid (every hex a general, non-parallelepiped one), boundary nodes
//    given a linear displacement field make the interior nodes follow it
//    exactly (constant strain is represented, and the incompatible modes'
//    Taylor correction keeps it so);
//  * pure bending: Saint-Venant's exact solution (quadratic in x, y, z)
//    prescribed at the nodes of a beam one element deep stores exactly
//    E I kappa^2 L / 2 (hex20 and tet10 contain every quadratic; hex8 through
//    its bubbles: no shear locking - without them, tried once, it stored
//    3.6 times more);
//  * mass: consistent mass gives the body's mass and its moments of inertia
//    exactly; lumped (HRZ) is diagonal, positive and keeps the mass.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "fe/assembly.hpp"
#include "fe/error.hpp"
#include "fe/meshers.hpp"
#include "fe/solid_element.hpp"
#include "fe/solid_types.hpp"

namespace rigflex::fe {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

const SolidProperties kSteel{2.1e11, 0.3, 7850.0, MassKind::Consistent};

// The mid-edge corner pairs of a type (fe/solid_element.hpp).
std::array<int, 2> mid_edge(const SolidType& t, int e) {
  return t.nodes == 10 ? kTetMidEdges[static_cast<size_t>(e)] : kHexMidEdges[static_cast<size_t>(e)];
}

// Reference nodes of each type on the unit cube / unit tetrahedron, in the
// node order of fe/solid_element.hpp.
std::vector<Vec3> reference_nodes(const SolidType& t) {
  std::vector<Vec3> x;
  if (t.nodes == 10) {
    x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    for (const auto& e : kTetMidEdges) x.push_back(0.5 * (x[e[0]] + x[e[1]]));
    return x;
  }
  x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
       Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  if (t.nodes == 20)
    for (const auto& e : kHexMidEdges) x.push_back(0.5 * (x[e[0]] + x[e[1]]));
  return x;
}

// Moves every node by up to `amount` (deterministic), keeping mid-edge nodes
// at their edges' midpoints so that edges stay straight.
std::vector<Vec3> distorted(const SolidType& t, double amount) {
  std::vector<Vec3> x = reference_nodes(t);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-amount, amount);
  const int corners = t.nodes == 10 ? 4 : 8;
  for (int a = 0; a < corners; ++a) x[a] += Vec3(u(rng), u(rng), u(rng));
  for (int e = 0; e < t.nodes - corners; ++e) {
    const std::array<int, 2> edge = mid_edge(t, e);
    x[corners + e] = 0.5 * (x[edge[0]] + x[edge[1]]);
  }
  return x;
}

MatrixXd rigid_modes(const std::vector<Vec3>& x) {
  MatrixXd R = MatrixXd::Zero(3 * static_cast<Eigen::Index>(x.size()), 6);
  for (size_t a = 0; a < x.size(); ++a) {
    const Eigen::Index r = 3 * static_cast<Eigen::Index>(a);
    R.block<3, 3>(r, 0).setIdentity();
    for (int k = 0; k < 3; ++k) R.block<3, 1>(r, 3 + k) = Vec3::Unit(k).cross(x[a]);
  }
  return R;
}

TEST(SolidElement, NullSpaceIsExactlyTheRigidBodyMotions) {
  for (const SolidType& t : solid_types()) {
    SCOPED_TRACE(t.name);
    const std::vector<Vec3> x = distorted(t, 0.15);
    const ElementMatrices e = t.matrices(x, kSteel);
    ASSERT_EQ(e.K.rows(), 3 * t.nodes);
    EXPECT_LT((e.K - e.K.transpose()).norm(), 1e-12 * e.K.norm());
    EXPECT_LT((e.K * rigid_modes(x)).norm(), 1e-9 * e.K.norm());
    const VectorXd lambda = Eigen::SelfAdjointEigenSolver<MatrixXd>(e.K).eigenvalues();
    const double top = lambda.maxCoeff();
    // Six zeros to rounding; the seventh is a real deformation (measured
    // ~1e-2 of the largest on these shapes; 1e-5 leaves room and still
    // catches an hourglass mode, which sits at rounding level).
    EXPECT_LT(std::abs(lambda(5)), 1e-10 * top);
    EXPECT_GT(lambda(6), 1e-5 * top);
  }
}

TEST(SolidElement, InvertedElementHasNegativeJacobianRatio) {
  for (const SolidType& t : solid_types()) {
    SCOPED_TRACE(t.name);
    std::vector<Vec3> x = reference_nodes(t);
    EXPECT_NEAR(solid_jacobian_ratio(x), 1.0, 1e-12);  // undistorted: constant Jacobian
    for (Vec3& p : x) p.z() = -p.z();                  // mirrored: left-handed node order
    EXPECT_LT(solid_jacobian_ratio(x), 0.0);
  }
}

// A unit-cube block, 2 x 2 x 2 cells, whose interior corner nodes are moved
// (and interior mid-edge nodes kept at their edges' midpoints).
Model patch_model(const SolidType& t) {
  Model m;
  m.materials["s"] = Material{"s", kSteel.E, kSteel.nu, kSteel.rho};
  NodeMerger merger(m);
  SolidBlockSpec spec;
  spec.id = "patch";
  spec.corners = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                  Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  spec.nx = spec.ny = spec.nz = 2;
  spec.element = t.name;
  spec.material = "s";
  mesh_solid_block(m, merger, spec);
  const NodeId centre = *merger.find(Vec3(0.5, 0.5, 0.5));
  m.nodes[m.node_index(centre)].x = Vec3(0.58, 0.44, 0.53);
  const int corners = t.nodes == 10 ? 4 : 8;
  for (const SolidElement& s : m.solids)
    for (int e = 0; e < t.nodes - corners; ++e) {
      const std::array<int, 2> edge = mid_edge(t, e);
      const NodeId a = s.nodes[static_cast<size_t>(edge[0])], b = s.nodes[static_cast<size_t>(edge[1])];
      if (a == centre || b == centre)
        m.nodes[m.node_index(s.nodes[static_cast<size_t>(corners + e)])].x = 0.5 * (m.position(a) + m.position(b));
    }
  m.validate();
  return m;
}

TEST(SolidPatch, LinearFieldIsExactOnDistortedMesh) {
  Eigen::Matrix3d A;
  A << 1.0, 0.4, -0.3, -0.2, 0.7, 0.5, 0.6, -0.1, -0.8;
  A *= 1e-3;
  const Vec3 b(0.01, -0.02, 0.03);
  for (const SolidType& t : solid_types()) {
    SCOPED_TRACE(t.name);
    const Model m = patch_model(t);
    SpMat K, M;
    assemble_full(m, K, M);
    // Translations only: solids leave the rotations empty.
    std::vector<Eigen::Index> inner, outer;
    VectorXd exact = VectorXd::Zero(K.rows());
    for (size_t i = 0; i < m.nodes.size(); ++i) {
      const Vec3& x = m.nodes[i].x;
      exact.segment<3>(6 * static_cast<Eigen::Index>(i)) = A * x + b;
      const bool interior = (x.array() > 1e-9).all() && (x.array() < 1 - 1e-9).all();
      for (int d = 0; d < 3; ++d) (interior ? inner : outer).push_back(6 * static_cast<Eigen::Index>(i) + d);
    }
    ASSERT_GE(inner.size(), 3u);
    const MatrixXd Kd = MatrixXd(K);
    const MatrixXd Kii = Kd(inner, inner), Kio = Kd(inner, outer);
    const VectorXd uo = exact(outer);
    const VectorXd ui = Kii.ldlt().solve(-Kio * uo);
    EXPECT_LT((ui - exact(inner)).cwiseAbs().maxCoeff(), 1e-12) << "interior nodes off the linear field";
  }
}

// Saint-Venant pure bending about y of a prismatic bar along x, curvature kappa.
Vec3 pure_bending(const Vec3& p, double kappa, double nu) {
  const double x = p.x(), y = p.y(), z = p.z();
  return {kappa * x * z, -nu * kappa * y * z, -0.5 * kappa * (x * x + nu * (z * z - y * y))};
}

TEST(SolidElement, PureBendingEnergyIsExactOneElementDeep) {
  const double L = 2.0, w = 0.3, h = 0.2, kappa = 1e-3;
  for (const SolidType& t : solid_types()) {
    SCOPED_TRACE(t.name);
    Model m;
    m.materials["s"] = Material{"s", kSteel.E, kSteel.nu, kSteel.rho};
    NodeMerger merger(m);
    SolidBlockSpec spec;
    spec.id = "bar";
    spec.corners = {Vec3(0, -w / 2, -h / 2), Vec3(L, -w / 2, -h / 2), Vec3(L, w / 2, -h / 2), Vec3(0, w / 2, -h / 2),
                    Vec3(0, -w / 2, h / 2),  Vec3(L, -w / 2, h / 2),  Vec3(L, w / 2, h / 2),  Vec3(0, w / 2, h / 2)};
    spec.nx = 4;
    spec.element = t.name;
    spec.material = "s";
    mesh_solid_block(m, merger, spec);
    SpMat K, M;
    assemble_full(m, K, M);
    VectorXd u = VectorXd::Zero(K.rows());
    for (size_t i = 0; i < m.nodes.size(); ++i)
      u.segment<3>(6 * static_cast<Eigen::Index>(i)) = pure_bending(m.nodes[i].x, kappa, kSteel.nu);
    const double energy = 0.5 * u.dot(K * u);
    const double exact = 0.5 * kSteel.E * (w * h * h * h / 12) * kappa * kappa * L;
    EXPECT_NEAR(energy / exact, 1.0, 1e-10);
  }
}

TEST(SolidElement, ConsistentMassGivesMassAndInertiaLumpedKeepsMass) {
  for (const SolidType& t : solid_types()) {
    SCOPED_TRACE(t.name);
    // A parallelepiped (a sheared, stretched cube): volume and inertia in
    // closed form through the affine map.
    std::vector<Vec3> x = reference_nodes(t);
    Eigen::Matrix3d F;
    F << 2.0, 0.3, 0.1, 0.0, 1.5, -0.2, 0.1, 0.0, 0.8;
    for (Vec3& p : x) p = F * p;
    const double ref_volume = t.nodes == 10 ? 1.0 / 6 : 1.0;
    const double volume = F.determinant() * ref_volume;
    const ElementMatrices e = t.matrices(x, kSteel);
    const MatrixXd R = rigid_modes(x);
    const MatrixXd rigid_mass = R.transpose() * e.M * R;
    EXPECT_NEAR(rigid_mass(0, 0) / (kSteel.rho * volume), 1.0, 1e-12);
    // Second moments about the origin: integral of x x' over the body,
    // by the affine map from the reference body's moments.
    // Unit tetrahedron: int x_i x_j = (1 + delta_ij) / 120; unit cube: 1/3
    // on the diagonal, 1/4 off it.
    const bool tet = t.nodes == 10;
    const Eigen::Matrix3d ref_second =
        (tet ? 1.0 / 120 : 0.25) * Eigen::Matrix3d::Ones() + (tet ? 1.0 / 120 : 1.0 / 12) * Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d S = kSteel.rho * F.determinant() * F * ref_second * F.transpose();
    const Eigen::Matrix3d J = S.trace() * Eigen::Matrix3d::Identity() - S;  // inertia tensor about the origin
    EXPECT_LT((rigid_mass.bottomRightCorner<3, 3>() - J).norm(), 1e-10 * J.norm());

    SolidProperties lumped = kSteel;
    lumped.mass = MassKind::Lumped;
    const MatrixXd Ml = t.matrices(x, lumped).M;
    EXPECT_EQ((Ml - MatrixXd(Ml.diagonal().asDiagonal())).norm(), 0.0);
    EXPECT_GT(Ml.diagonal().minCoeff(), 0.0);
    EXPECT_NEAR(Ml.diagonal().sum() / (3 * kSteel.rho * volume), 1.0, 1e-12);
  }
}

TEST(SolidModel, InvertedSolidIsRefusedByName) {
  Model m;
  m.materials["s"] = Material{"s", kSteel.E, kSteel.nu, kSteel.rho};
  const std::vector<Vec3> x = reference_nodes(*solid_type_named("hex8"));
  SolidElement s;
  s.id = "block:1";
  s.material = "s";
  for (size_t a = 0; a < x.size(); ++a) s.nodes.push_back(m.add_node(static_cast<NodeId>(a + 1), x[a]));
  std::swap(s.nodes[1], s.nodes[3]);  // corners 1-4 clockwise
  m.solids.push_back(s);
  try {
    m.validate();
    FAIL() << "an inverted hex8 was accepted";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().kind, "solid");
    EXPECT_EQ(e.where().id, "block:1");
    EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rigflex::fe
