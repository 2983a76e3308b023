// A point mass on shell nodes (fe/shell_point_mass.hpp): where its inertia
// goes, and that the model's rigid-body mass stays exact. The modal side
// (no drilling mode, mesh-independent modes) is in
// tests/reduction/test_thick_plate_modes.cpp and test_modal_summary.cpp.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "fe/element_loop.hpp"
#include "fe/meshers.hpp"
#include "fe/node_merger.hpp"
#include "fe/shell_point_mass.hpp"
#include "fe/skew.hpp"
#include "support/frame_models.hpp"

namespace rigflex {
namespace {

// A 2 x 1 m plate in a tilted plane (normal not along any axis), 12 x 6.
fe::PatchNodes tilted_plate(fe::Model& m, bool quadratic) {
  m.shell_sections["plate"] = {"plate", "steel", 0.01};
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.4, fe::Vec3(1, 2, 3).normalized())).toRotationMatrix();
  fe::PatchSpec p;
  p.id = "plate";
  p.corners = {R * fe::Vec3(0, 0, 0), R * fe::Vec3(2, 0, 0), R * fe::Vec3(2, 1, 0), R * fe::Vec3(0, 1, 0)};
  p.nx = 12;
  p.ny = 6;
  p.quadratic = quadratic;
  p.section = "plate";
  fe::NodeMerger merger(m);
  return fe::mesh_shell_patch(m, merger, p);
}

// Phi' M Phi over the six rigid motions about the origin, M assembled dense.
Eigen::Matrix<double, 6, 6> rigid_mass(const fe::Model& m) {
  const auto n = static_cast<Eigen::Index>(6 * m.nodes.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  fe::for_each_element(m, [&](const std::vector<long>& dofs, const Eigen::MatrixXd&, const Eigen::MatrixXd& Me) {
    for (size_t i = 0; i < dofs.size(); ++i)
      for (size_t j = 0; j < dofs.size(); ++j)
        M(dofs[i], dofs[j]) += Me(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  });
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(n, 6);
  for (size_t k = 0; k < m.nodes.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(6 * k);
    Phi.block<3, 3>(r, 0).setIdentity();
    Phi.block<3, 3>(r, 3) = -fe::skew(m.nodes[k].x);
    Phi.block<3, 3>(r + 3, 3).setIdentity();
  }
  return Phi.transpose() * M * Phi;
}

// The closed form of a point mass's rigid-body mass about the origin.
Eigen::Matrix<double, 6, 6> point_rigid_mass(const fe::PointMass& p, const fe::Vec3& x) {
  Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
  T.block<3, 3>(0, 3) = -fe::skew(x);
  Eigen::Matrix<double, 6, 6> M6 = Eigen::Matrix<double, 6, 6>::Zero();
  M6.topLeftCorner<3, 3>() = p.mass * Eigen::Matrix3d::Identity();
  const auto& J = p.inertia;
  M6.bottomRightCorner<3, 3>() << J[0], J[3], J[4], J[3], J[1], J[5], J[4], J[5], J[2];
  return T.transpose() * M6 * T;
}

// Rigid motions are exact: the plate with masses (full inertia tensors, one
// in the middle, one at a corner, footprints of several elements) has the
// rigid-body mass of the bare plate plus the masses' closed forms, on 4-
// and 8-node meshes in a plane whose normal is along no axis.
TEST(ShellPointMass, TheRigidBodyMassIsExact) {
  for (const bool quadratic : {false, true}) {
    fe::Model m = test::steel_model();
    const fe::PatchNodes g = tilted_plate(m, quadratic);
    const Eigen::Matrix<double, 6, 6> bare = rigid_mass(m);
    m.point_masses.push_back({"middle", g.at(g.rows / 2, g.cols / 2), 30.0, {2.0, 3.0, 4.0, 0.3, -0.2, 0.1}});
    m.point_masses.push_back({"corner", g.at(g.rows - 1, g.cols - 1), 10.0, {0.5, 0.2, 0.4, 0, 0.1, 0}});
    Eigen::Matrix<double, 6, 6> expected = bare;
    for (const fe::PointMass& p : m.point_masses) expected += point_rigid_mass(p, m.position(p.node));
    const std::vector<fe::PointMassMatrix> pm = fe::point_mass_matrices(m);
    ASSERT_EQ(pm.size(), 2u);
    for (const auto& p : pm) EXPECT_GT(p.dofs.size(), 6u) << "quadratic " << quadratic;
    const Eigen::Matrix<double, 6, 6> got = rigid_mass(m);
    EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm()) << "quadratic " << quadratic << "\n" << got - expected;
  }
}

// The footprint has a fixed size: the shells around the node, and those
// reached within the mass's largest radius of gyration (here 0.4 m, over
// two elements), and no more than one element beyond it.
TEST(ShellPointMass, TheFootprintSpansTheRadiusOfGyration) {
  for (const bool quadratic : {false, true}) {
    fe::Model m = test::steel_model();
    const fe::PatchNodes g = tilted_plate(m, quadratic);
    const fe::NodeId middle = g.at(g.rows / 2, g.cols / 2);
    m.point_masses.push_back({"middle", middle, 25.0, {4.0, 4.0, 4.0, 0, 0, 0}});  // sqrt(4 / 25) = 0.4 m
    const fe::PointMassMatrix pm = fe::point_mass_matrices(m).front();
    const double h = 2.0 / 12.0 * std::sqrt(2.0);  // an element's diagonal
    double reach = 0.0;
    for (size_t k = 6; k < pm.dofs.size(); k += 3) {
      const fe::Vec3& x = m.nodes[static_cast<size_t>(pm.dofs[k] / 6)].x;
      reach = std::max(reach, (x - m.position(middle)).norm());
    }
    EXPECT_GT(reach, 0.4) << quadratic;
    EXPECT_LE(reach, 0.4 + h + 1e-12) << quadratic;
  }
}

// Two 1 x 1 m plates (4 x 4) meeting along the y axis at `angle` degrees
// between their planes; returns the node in the middle of the fold.
fe::NodeId folded_plates(fe::Model& m, double angle) {
  m.shell_sections["plate"] = {"plate", "steel", 0.01};
  const double a = angle * std::acos(-1.0) / 180.0;
  fe::NodeMerger merger(m);
  fe::PatchSpec p;
  p.section = "plate";
  p.nx = p.ny = 4;
  p.id = "flat";
  p.corners = {fe::Vec3(-1, 0, 0), fe::Vec3(0, 0, 0), fe::Vec3(0, 1, 0), fe::Vec3(-1, 1, 0)};
  fe::mesh_shell_patch(m, merger, p);
  p.id = "bent";
  const fe::Vec3 out(std::cos(a), 0, std::sin(a));
  p.corners = {fe::Vec3(0, 0, 0), out, out + fe::Vec3(0, 1, 0), fe::Vec3(0, 1, 0)};
  fe::mesh_shell_patch(m, merger, p);
  for (const fe::Node& n : m.nodes)
    if ((n.x - fe::Vec3(0, 0.5, 0)).norm() < 1e-9) return n.id;
  return 0;
}

// Where the node's own rotations are physical DOFs the mass keeps them, on
// its node's six DOFs as given: no rotary inertia, a support of a rotation
// (a symmetry plane) or a spring at the node, a
// fold whose walls lie more than 5 degrees off their mean plane (one wall's
// drilling rotation is the other's bending rotation): 90 and 12 degrees.
// An 8-degree fold (4 degrees each) counts as one plane.
TEST(ShellPointMass, ANodeWithPhysicalRotationsKeepsThePlainMass) {
  const std::array<double, 6> J{1.0, 1.0, 1.0, 0, 0, 0};
  auto dofs_of = [](const fe::Model& m) { return fe::point_mass_matrices(m).front().dofs.size(); };
  {
    fe::Model m = test::steel_model();
    const fe::NodeId node = folded_plates(m, 0.0);
    m.point_masses.push_back({"plain", node, 10.0, {}});
    EXPECT_EQ(dofs_of(m), 6u) << "no rotary inertia";
    m.point_masses.front().inertia = J;
    EXPECT_GT(dofs_of(m), 6u) << "flat";
    m.supports.push_back({"held", node, {false, false, true, false, false, false}});
    EXPECT_GT(dofs_of(m), 6u) << "a support of a translation";
    m.supports.back().fixed[3] = true;  // a symmetry plane's rotation
    EXPECT_EQ(dofs_of(m), 6u) << "a support of a rotation";
    m.supports.pop_back();
    m.springs.push_back({"spring", node, std::nullopt, {0, 0, 0, 0, 0, 1e3}, std::nullopt, std::nullopt});
    EXPECT_EQ(dofs_of(m), 6u) << "a spring at the node";
  }
  for (const auto& [angle, plain] : {std::pair{90.0, true}, std::pair{12.0, true}, std::pair{8.0, false}}) {
    fe::Model m = test::steel_model();
    m.point_masses.push_back({"fold", folded_plates(m, angle), 10.0, J});
    EXPECT_EQ(dofs_of(m) == 6u, plain) << angle << " degrees";
  }
}

}  // namespace
}  // namespace rigflex
