// Distributing coupling (RBE3), fe/distributing_coupling.hpp:
//  * its kinematics reproduce any rigid motion of the nodes at the reference
//    exactly (translation and rotation), and average anything else;
//  * nodes on one line (or fewer than three) are refused: they leave the
//    rotation about the line undefined;
//  * in a model: a free body keeps its six rigid-body modes and gains exactly
//    the reference's mass and inertia (rigid motions pass through the
//    coupling exactly), and a heavy mass hung on a solid bar's end face
//    through it vibrates as the closed-form spring-mass systems predict
//    (axial k = E A / L, bending k = 3 E I / L^3), the face left free to
//    deform.
#include <gtest/gtest.h>

#include <random>

#include "fe/assembly.hpp"
#include "fe/distributing_coupling.hpp"
#include "fe/error.hpp"
#include "fe/mass_properties.hpp"
#include "fe/meshers.hpp"
#include "linalg/eigen_solver.hpp"

namespace rigflex::fe {
namespace {

TEST(DistributingCoupling, ReproducesRigidMotionsExactly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> w;
  for (int i = 0; i < 7; ++i) {
    x.emplace_back(u(rng), u(rng), 0.3 * u(rng));
    w.push_back(1.5 + u(rng));
  }
  const Vec3 ref(0.2, -0.4, 0.9);
  for (const auto& weights : {std::vector<double>{}, w}) {
    const auto G = distributing_link(ref, x, weights);
    ASSERT_TRUE(G);
    const Vec3 a(0.01, -0.02, 0.005), phi(0.003, 0.001, -0.004);
    Eigen::VectorXd motion(3 * x.size());
    for (size_t i = 0; i < x.size(); ++i) motion.segment<3>(3 * static_cast<Eigen::Index>(i)) = a + phi.cross(x[i]);
    const Eigen::VectorXd r = *G * motion;
    EXPECT_LT((r.head<3>() - (a + phi.cross(ref))).norm(), 1e-15);
    EXPECT_LT((r.tail<3>() - phi).norm(), 1e-15);
  }
}

TEST(DistributingCoupling, AveragesTranslationsByWeight) {
  const std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  const std::vector<double> w{1, 2, 3, 4};
  const auto G = distributing_link(Vec3(0.5, 0.5, 0.2), x, w);  // reference off the weighted centroid
  ASSERT_TRUE(G);
  Eigen::VectorXd same(12);
  for (int i = 0; i < 4; ++i) same.segment<3>(3 * i) = Vec3(0.1, -0.2, 0.3);
  EXPECT_LT(((*G * same).head<3>() - Vec3(0.1, -0.2, 0.3)).norm(), 1e-15);
  EXPECT_LT((*G * same).tail<3>().norm(), 1e-15);
  // Every node moved by the same vector: the reference follows it; one node
  // moved alone: the reference's translation at the weighted centroid is
  // w_i / W of it (checked through the centroid's own link).
  const Vec3 c = (1 * x[0] + 2 * x[1] + 3 * x[2] + 4 * x[3]) / 10;
  const auto Gc = distributing_link(c, x, w);
  Eigen::VectorXd one = Eigen::VectorXd::Zero(12);
  one(3 * 2 + 2) = 1.0;  // node 3 up by 1
  EXPECT_NEAR((*Gc * one)(2), 0.3, 1e-15);
}

TEST(DistributingCoupling, CollinearOrTooFewNodesAreRefused) {
  EXPECT_FALSE(distributing_link(Vec3::Zero(), {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, {}));
  EXPECT_FALSE(distributing_link(Vec3::Zero(), {Vec3(0, 0, 0), Vec3(1, 1, 0)}, {}));
  EXPECT_TRUE(distributing_link(Vec3::Zero(), {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1e-3, 0)}, {}));

  Model m;
  for (int i = 0; i < 4; ++i) m.add_node(i + 1, Vec3(i, 0, 0));
  m.distributing_couplings.push_back({"line", 4, {1, 2, 3}, {}});
  try {
    m.validate();
    FAIL() << "collinear nodes accepted";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().id, "line");
    EXPECT_NE(std::string(e.what()).find("one line"), std::string::npos) << e.what();
  }
}

// What validate() refuses, each naming the coupling and the offending key.
TEST(DistributingCoupling, ChainsAndBadWeightsAreRefused) {
  auto base = [] {
    Model m;
    // A square of nodes 1-4, references 5 and 6 above it, a node 7 beside.
    const Vec3 p[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}, {0.5, 0.5, 2}, {2, 0, 0}};
    for (int i = 0; i < 7; ++i) m.add_node(i + 1, p[i]);
    return m;
  };
  auto refused = [](const Model& m, const std::string& id, const std::string& key, const std::string& words) {
    try {
      m.validate();
      ADD_FAILURE() << words << ": accepted";
    } catch (const ModelError& e) {
      EXPECT_EQ(e.where().id, id) << e.what();
      EXPECT_EQ(e.where().key, key) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  {  // a node of one is the reference of another: its motion would be read as zero
    Model m = base();
    m.distributing_couplings.push_back({"upper", 6, {1, 2, 5}, {}});
    m.distributing_couplings.push_back({"lower", 5, {1, 2, 3, 4}, {}});
    refused(m, "upper", "nodes", "reference of a distributing coupling");
  }
  {  // a node that a rigid coupling drives
    Model m = base();
    m.couplings.push_back({"tie", 7, {4}, {true, true, true, true, true, true}});
    m.distributing_couplings.push_back({"hub", 5, {1, 2, 3, 4}, {}});
    refused(m, "hub", "nodes", "dependent of a rigid coupling");
  }
  {  // a rigid coupling hung on a distributing reference
    Model m = base();
    m.distributing_couplings.push_back({"hub", 5, {1, 2, 3, 4}, {}});
    m.couplings.push_back({"tie", 5, {6}, {true, true, true, true, true, true}});
    refused(m, "tie", "reference", "driven by a distributing coupling");
  }
  {  // one reference, two couplings
    Model m = base();
    m.distributing_couplings.push_back({"a", 5, {1, 2, 3}, {}});
    m.distributing_couplings.push_back({"b", 5, {2, 3, 4}, {}});
    refused(m, "b", "reference", "already the reference");
  }
  {
    Model m = base();
    m.distributing_couplings.push_back({"hub", 5, {1, 2, 3, 4}, {1, 1, 0, 1}});
    refused(m, "hub", "weights", "positive");
  }
  {
    Model m = base();
    m.distributing_couplings.push_back({"hub", 5, {1, 2, 3, 4}, {1, 1}});
    refused(m, "hub", "weights", "2 weights for 4 nodes");
  }
  {
    Model m = base();
    m.distributing_couplings.push_back({"hub", 5, {1, 2, 3, 3}, {}});
    refused(m, "hub", "nodes", "twice");
  }
}

const Material kSteel{"steel", 2.1e11, 0.3, 7850.0};

// A hex20 bar along x, L x b x b, one end at x = 0.
Model bar(double L, double b, int n) {
  Model m;
  m.materials["steel"] = kSteel;
  NodeMerger merger(m);
  SolidBlockSpec spec;
  spec.id = "bar";
  spec.corners = {Vec3(0, -b / 2, -b / 2), Vec3(L, -b / 2, -b / 2), Vec3(L, b / 2, -b / 2), Vec3(0, b / 2, -b / 2),
                  Vec3(0, -b / 2, b / 2),  Vec3(L, -b / 2, b / 2),  Vec3(L, b / 2, b / 2),  Vec3(0, b / 2, b / 2)};
  spec.nx = n;
  spec.ny = spec.nz = 2;
  spec.element = "hex20";
  spec.material = "steel";
  mesh_solid_block(m, merger, spec);
  return m;
}

std::vector<NodeId> nodes_at_x(const Model& m, double x) {
  std::vector<NodeId> ids;
  for (const Node& n : m.nodes)
    if (std::abs(n.x.x() - x) < 1e-9) ids.push_back(n.id);
  return ids;
}

TEST(DistributingCoupling, FreeBodyGainsTheReferenceMassAndKeepsItsRigidModes) {
  const double L = 1.0, b = 0.1;
  Model m = bar(L, b, 4);
  const NodeId ref = m.add_node(1000, Vec3(L + 0.3, 0.05, 0.02));
  m.distributing_couplings.push_back({"end", ref, nodes_at_x(m, L), {}});
  const double mass = 50.0;
  m.point_masses.push_back({"weight", ref, mass, {2.0, 3.0, 4.0, 0.1, 0.0, 0.0}});
  const AssembledSystem sys = assemble(m);
  // Rigid-body modes of everything: six zero eigenvalues, the seventh real.
  const Eigen::MatrixXd K = Eigen::MatrixXd(sys.K), M = Eigen::MatrixXd(sys.M);
  const linalg::EigenResult r = linalg::solve_dense(K, M, 8, -1.0);
  ASSERT_GE(r.eigenvalues.size(), 7);
  EXPECT_LT(std::abs(r.eigenvalues(5)), 1e-6 * r.eigenvalues(6));
  // The 6 x 6 rigid-body mass about the origin (u = a + theta x x):
  // [m I, -m [c]x; m [c]x, J_origin], in closed form for the bar (a box
  // along x from 0 to L) plus the point mass at its offset with its own
  // inertia, against R' M R of the assembled system.
  const Eigen::MatrixXd R = rigid_body_modes_free(m, sys.dofs, Vec3::Zero());
  const Eigen::MatrixXd rigid = R.transpose() * M * R;
  auto skew = [](const Vec3& v) {
    Eigen::Matrix3d s;
    s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return s;
  };
  auto body = [&](double mb, const Vec3& c, const Eigen::Matrix3d& J_origin) {
    Eigen::Matrix<double, 6, 6> B;
    B << mb * Eigen::Matrix3d::Identity(), -mb * skew(c), mb * skew(c), J_origin;
    return B;
  };
  const double bar_mass = kSteel.rho * L * b * b;
  const Eigen::Matrix3d J_bar =
      bar_mass * Eigen::Vector3d(b * b / 6, L * L / 3 + b * b / 12, L * L / 3 + b * b / 12).asDiagonal();
  const Vec3 p = m.position(ref);
  Eigen::Matrix3d J_point;
  J_point << 2.0, 0.1, 0.0, 0.1, 3.0, 0.0, 0.0, 0.0, 4.0;
  J_point += mass * (p.squaredNorm() * Eigen::Matrix3d::Identity() - p * p.transpose());
  const Eigen::Matrix<double, 6, 6> expected = body(bar_mass, Vec3(L / 2, 0, 0), J_bar) + body(mass, p, J_point);
  EXPECT_LT((rigid - expected).norm(), 1e-11 * expected.norm()) << rigid << "\n\n" << expected;
}

TEST(DistributingCoupling, HeavyEndMassVibratesAsTheSpringMassClosedForms) {
  const double L = 2.0, b = 0.1;
  Model m = bar(L, b, 10);
  for (NodeId id : nodes_at_x(m, 0.0)) m.supports.push_back({"root", id, {true, true, true, false, false, false}});
  const std::vector<NodeId> face = nodes_at_x(m, L);
  const NodeId ref = m.add_node(1000, Vec3(L, 0, 0));
  m.distributing_couplings.push_back({"end", ref, face, {}});
  const double bar_mass = kSteel.rho * L * b * b, M = 100 * bar_mass;
  m.point_masses.push_back({"weight", ref, M, {}});
  const AssembledSystem sys = assemble(m);
  const linalg::EigenResult r = linalg::solve_dense(Eigen::MatrixXd(sys.K), Eigen::MatrixXd(sys.M), 3, -1.0);
  const Eigen::VectorXd f = r.frequencies_hz();
  const double A = b * b, I = b * b * b * b / 12;
  // Spring-mass with the bar's own mass by Rayleigh (1/3 axial, 33/140 bending).
  const double f_bending = std::sqrt(3 * kSteel.E * I / (L * L * L) / (M + 33.0 / 140 * bar_mass)) / (2 * M_PI);
  const double f_axial = std::sqrt(kSteel.E * A / L / (M + bar_mass / 3)) / (2 * M_PI);
  // Modes 1-2: bending in y and z (equal by symmetry); mode 3: axial (the
  // mass has no rotary inertia, so no torsion mode comes below it).
  // Tolerance 1 %, from the modelling, not the coupling: fully integrated
  // hex20 of aspect 4 are slightly stiff in bending (measured +0.58 % here,
  // +0.27 % with twice the elements along the bar; shear flexibility at
  // L / b = 20 would lower it by 0.1 %), and equal weights put equal nodal
  // forces on the face's corner and mid-edge nodes, a non-uniform traction
  // whose local compliance grows as the mesh resolves it (axial -0.14 %
  // here, -0.49 % with twice the elements). A lost lever arm, a wrong
  // weight sum or a mass not passed through moves these by far more.
  EXPECT_NEAR(f(0) / f_bending, 1.0, 1e-2);
  EXPECT_NEAR(f(1) / f_bending, 1.0, 1e-2);
  EXPECT_NEAR(f(2) / f_axial, 1.0, 1e-2);
  std::printf("  bending %.4f Hz (closed form %.4f), axial %.4f Hz (closed form %.4f)\n", f(0), f_bending, f(2),
              f_axial);
}

TEST(DistributingCoupling, SupportOnTheReferenceIsRefused) {
  Model m = bar(1.0, 0.1, 2);
  const std::vector<NodeId> face = nodes_at_x(m, 1.0);
  const NodeId ref = m.add_node(1000, Vec3(1.0, 0, 0));
  m.distributing_couplings.push_back({"end", ref, face, {}});
  m.supports.push_back({"fix", ref, {true, false, false, false, false, false}});
  try {
    assemble(m);
    FAIL() << "a support on a driven reference was accepted";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().id, "fix");
  }
}

}  // namespace
}  // namespace rigflex::fe
