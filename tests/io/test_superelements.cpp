// Reduced frames placed in a model as superelements (fe::Superelement, a
// model file's `superelements:`), and the interface chosen per node.
//  - A table frame cut in two substructures - a base of four clamped
//    columns and a ring beam, and a deck plate of 8-node shells carrying a
//    block - meeting at the four column tops: each part reduced by
//    Craig-Bampton onto the four nodes (all six DOFs; the base grounded,
//    the deck free-free), exported, and the two placed in a model of their
//    own. Its lowest ten modes (7.1 .. 45.3 Hz) match the full frame's
//    within 0.1 % (the issue's acceptance). Measured, worst of the ten:
//    3.3e-3 with 5 fixed-interface modes per part, 7.0e-4 with 30, 8.7e-6
//    with 60 (used); the 5-mode case is asserted to fail the tolerance, so
//    the comparison can fail.
//  - The assembled model reduced again (Guyan onto the column tops) gives
//    the stiffness the full frame's Guyan reduction gives, to round-off: a
//    Craig-Bampton part's stiffness on its interface is the exact static
//    condensation.
//  - A free part placed alone keeps the part's mass, CoG and inertia.
//  - A partly supported interface node keeps its free DOFs; DOFs chosen per
//    node; both exported and read back.
#include <gtest/gtest.h>

#include <string>

#include "fe/error.hpp"
#include "fe/mass_properties.hpp"
#include "io/model_reader.hpp"
#include "io/reduced_export.hpp"
#include "reduction/frame_reduction.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/temp_files.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {
namespace fs = std::filesystem;

const std::string kMaterials = R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
beam_sections:
  column: {material: steel, shape: box, width: 0.1, height: 0.1, wall: 0.005}
  ring: {material: steel, shape: rectangle, width: 0.04, height: 0.08}
shell_sections:
  deck: {material: steel, thickness: 0.01}
)";

const std::string kBase = R"(members:
  - {id: c1, from: [0, 0, 0], to: [0, 0, 1.5], elements: 6, section: column}
  - {id: c2, from: [2, 0, 0], to: [2, 0, 1.5], elements: 6, section: column}
  - {id: c3, from: [2, 1, 0], to: [2, 1, 1.5], elements: 6, section: column}
  - {id: c4, from: [0, 1, 0], to: [0, 1, 1.5], elements: 6, section: column}
  - {id: r1, from: [0, 0, 1.25], to: [2, 0, 1.25], elements: 8, section: ring}
  - {id: r2, from: [0, 1, 1.25], to: [2, 1, 1.25], elements: 8, section: ring}
supports:
  - {plane: [[0, 0, 0], [0, 0, 1]], dofs: all}
)";

const std::string kDeck = R"(shell_patches:
  - {id: p, corners: [[0, 0, 1.5], [2, 0, 1.5], [2, 1, 1.5], [0, 1, 1.5]], divisions: [8, 4], section: deck}
point_masses:
  - {id: block, at: [1.5, 0.5, 1.5], mass: 60}
)";

Eigen::VectorXd lowest_modes(const fe::Model& model, int count) {
  const reduction::ModalAnalysis a = test::checked_modal_analysis(model, count);
  EXPECT_LT(a.result.residuals.maxCoeff(), 1e-8);
  return a.result.frequencies_hz();
}

fe::Model model_of(const std::string& text, const fs::path& file) { return io::parse_model(text, file.string()).model; }

// The four column tops, by id, in a model that has them.
std::vector<fe::NodeId> tops(const fe::Model& m) {
  std::vector<fe::NodeId> ids;
  for (const fe::Vec3& p : {fe::Vec3(0, 0, 1.5), fe::Vec3(2, 0, 1.5), fe::Vec3(2, 1, 1.5), fe::Vec3(0, 1, 1.5)})
    for (const fe::Node& n : m.nodes)
      if ((n.x - p).norm() < 1e-9) ids.push_back(n.id);
  return ids;
}

reduction::ReducedFrame reduce(fe::Model m, reduction::ReductionMethod method, int modes) {
  m.node_sets["tops"] = tops(m);
  EXPECT_EQ(m.node_sets["tops"].size(), 4u);
  reduction::FrameReductionOptions o;
  o.interface_set = "tops";
  o.retained = reduction::InterfaceDofs::all;
  o.method = method;
  o.modes = modes;
  return reduction::reduce_frame(m, o);
}

// The two parts reduced with `modes` fixed-interface modes each, placed in a model.
fe::Model assembled(const test::TempDir& dir, int modes) {
  const auto cb = reduction::ReductionMethod::craig_bampton;
  io::write_reduced_frame(dir.path() / "base", reduce(model_of(kMaterials + kBase, dir.path() / "b.yaml"), cb, modes));
  io::write_reduced_frame(dir.path() / "deck", reduce(model_of(kMaterials + kDeck, dir.path() / "d.yaml"), cb, modes));
  return model_of("superelements:\n  - {id: base, reduced: base}\n  - {id: deck, reduced: deck}\n",
                  dir.path() / "table.yaml");
}

TEST(Superelements, TwoSubstructuresReducedAndPlacedGiveTheFullFramesModes) {
  test::TempDir dir("superelements");
  const fe::Model full = model_of(kMaterials + kBase + kDeck, dir.path() / "full.yaml");
  const Eigen::VectorXd f_full = lowest_modes(full, 10);

  const fe::Model table = assembled(dir, 60);
  ASSERT_EQ(table.superelements.size(), 2u);
  EXPECT_EQ(table.superelements[0].interface.size(), 24u);
  EXPECT_EQ(table.superelements[0].modal_nodes.size(), 60u);
  const Eigen::VectorXd f_table = lowest_modes(table, 10);
  double worst = 0;
  for (Eigen::Index k = 0; k < 10; ++k) {
    EXPECT_NEAR(f_table(k) / f_full(k), 1.0, 1e-3) << "mode " << k + 1;
    worst = std::max(worst, std::abs(f_table(k) / f_full(k) - 1.0));
  }
  std::printf("60 modes per part: worst of the lowest ten %.2e (full %.3f .. %.3f Hz)\n", worst, f_full(0), f_full(9));

  // Too few modes per part miss the deck's plate modes: the comparison can fail.
  test::TempDir coarse_dir("superelements-coarse");
  const Eigen::VectorXd f_coarse = lowest_modes(assembled(coarse_dir, 5), 10);
  double coarse = 0;
  for (Eigen::Index k = 0; k < 10; ++k) coarse = std::max(coarse, std::abs(f_coarse(k) / f_full(k) - 1.0));
  std::printf("5 modes per part: worst %.2e\n", coarse);
  EXPECT_GT(coarse, 1e-3);
}

TEST(Superelements, TheAssembledModelReducedAgainKeepsTheStaticCondensation) {
  test::TempDir dir("superelements-again");
  const fe::Model full = model_of(kMaterials + kBase + kDeck, dir.path() / "full.yaml");
  const reduction::ReducedFrame direct = reduce(full, reduction::ReductionMethod::guyan, 0);
  const reduction::ReducedFrame again = reduce(assembled(dir, 12), reduction::ReductionMethod::guyan, 0);
  ASSERT_EQ(again.K.rows(), direct.K.rows());
  EXPECT_LT((again.K - direct.K).cwiseAbs().maxCoeff() / direct.K.cwiseAbs().maxCoeff(), 1e-8);
}

// A free-free part's reduced mass moved rigidly is the part's mass; its
// modal coordinates take no part in a rigid motion (fe::rigid_body_modes).
TEST(Superelements, AFreePartKeepsItsMassProperties) {
  test::TempDir dir("superelements-mass");
  const fe::Model deck = model_of(kMaterials + kDeck, dir.path() / "d.yaml");
  io::write_reduced_frame(dir.path() / "deck", reduce(deck, reduction::ReductionMethod::craig_bampton, 10));
  const fe::Model placed = model_of("superelements:\n  - {id: deck, reduced: deck}\n", dir.path() / "m.yaml");
  const fe::MassProperties a = fe::mass_properties(deck), b = fe::mass_properties(placed);
  EXPECT_NEAR(b.mass, a.mass, 1e-9 * a.mass);
  EXPECT_NEAR((b.cog - a.cog).norm(), 0.0, 1e-9);
  EXPECT_NEAR((b.inertia - a.inertia).norm(), 0.0, 1e-9 * a.inertia.norm());
}

TEST(Superelements, APartlySupportedInterfaceNodeAndDofsChosenPerNode) {
  test::TempDir dir("superelements-dofs");
  fe::Model base = model_of(kMaterials + kBase, dir.path() / "b.yaml");
  const std::vector<fe::NodeId> t = tops(base);
  base.node_sets["tops"] = t;
  base.supports.push_back({"roller", t[0], fe::DofMask{false, false, true, false, false, false}});
  reduction::FrameReductionOptions o;
  o.interface_set = "tops";
  o.retained = reduction::InterfaceDofs::all;
  o.node_dofs[t[1]] = fe::DofMask{true, true, true, false, false, true};
  const reduction::ReducedFrame r = reduction::reduce_frame(base, o);
  // 5 (UZ held) + 4 (chosen) + 6 + 6.
  ASSERT_EQ(r.interface_dofs.size(), 21u);
  EXPECT_EQ(r.interface_dofs[2].local, 3);  // node 1: UX UY RX ...
  EXPECT_EQ(r.interface_dofs[8].local, 5);  // node 2: UX UY UZ RZ
  EXPECT_LT(r.checks.static_flexibility_error, 1e-8);
  io::write_reduced_frame(dir.path() / "base", r);
  const reduction::ReducedFrame back = io::read_reduced_frame(dir.path() / "base");
  ASSERT_EQ(back.interface_dofs.size(), 21u);
  EXPECT_EQ(back.interface_dofs[8].local, 5);

  // A DOF chosen for a node outside the interface, or a node that keeps none, is refused.
  o.node_dofs[t[1]] = fe::DofMask{};
  EXPECT_THROW(reduction::reduce_frame(base, o), fe::ModelError);
  o.node_dofs.clear();
  o.node_dofs[999999] = fe::DofMask{true, false, false, false, false, false};
  EXPECT_THROW(reduction::reduce_frame(base, o), fe::ModelError);
}

}  // namespace
}  // namespace rigflex
