// Exports to other solvers: a model as a CalculiX / Abaqus deck
// (io/calculix_deck.hpp, `rigflex export --deck`) and a reduced frame as
// Nastran DMIG cards and Abaqus matrix input (io/reduced_solver_formats.hpp).
//  - A model of beams (four section shapes), 4- and 8-node shells, hex20
//    solids, point masses and springs written as a deck and read back by
//    rigflex's deck reader gives the same ten modes to round-off: shells and
//    solids are written as they are; each beam comes back as two (the
//    deck's B32R has a middle node), so the reference is the model with its
//    beams split at their midpoints (unsplit, the finer beam mesh moves the
//    modes by up to 1e-4).
//  - For Abaqus: a circle's radius and a point mass's rotary inertia
//    (ROTARYI) survive the round trip; for CalculiX the rotary inertia is
//    refused (ccx 2.20 has none).
//  - DMIG and Abaqus matrices read back by a parser of the cards' own
//    layout give K, M and C: to the 10 digits of a DMIG large field, and
//    exactly (17 digits) for Abaqus; every DOF pair once.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "io/abaqus_deck.hpp"
#include "io/calculix_deck.hpp"
#include "io/model_reader.hpp"
#include "io/reduced_solver_formats.hpp"
#include "reduction/frame_reduction.hpp"
#include "reduction/modal_analysis.hpp"
#include "support/test_support.hpp"

namespace rigflex {
namespace {

const std::string kMixed = R"(materials:
  steel: {E: 2.1e11, nu: 0.3, rho: 7850}
beam_sections:
  tube: {material: steel, shape: tube, diameter: 0.1, wall: 0.005}
  box: {material: steel, shape: box, width: 0.08, height: 0.12, web_thickness: 0.004, flange_thickness: 0.006}
  bar: {material: steel, shape: rectangle, width: 0.03, height: 0.06}
  rod: {material: steel, shape: circle, diameter: 0.04}
shell_sections:
  plate: {material: steel, thickness: 0.01}
members:
  - {id: c1, from: [0, 0, 0], to: [0, 0, 1], elements: 4, section: tube}
  - {id: c2, from: [1, 0, 0], to: [1, 0, 1], elements: 4, section: box}
  - {id: top, from: [0, 0, 1], to: [1, 0, 1], elements: 4, section: bar}
  - {id: stay, from: [0, 0, 0.5], to: [1, 0, 1], elements: 3, section: rod}
shell_patches:
  - {id: fin, corners: [[0, 0, 1], [1, 0, 1], [1, 0, 1.5], [0, 0, 1.5]], divisions: [4, 2], section: plate}
  - {id: flap, corners: [[0, 0, 1.5], [1, 0, 1.5], [1, 0.4, 1.5], [0, 0.4, 1.5]], divisions: [4, 2], order: linear,
     section: plate}
solid_blocks:
  - {id: pad, corners: [[3, 0, 0], [3.4, 0, 0], [3.4, 0.2, 0], [3, 0.2, 0], [3, 0, 0.1], [3.4, 0, 0.1], [3.4, 0.2, 0.1],
     [3, 0.2, 0.1]], divisions: [4, 2, 1], element: hex20, material: steel}
point_masses:
  - {id: lamp, at: [1, 0, 1], mass: 8)";

const std::string kRest = R"(
springs:
  - {id: k1, at: [0.5, 0.4, 1.5], stiffness: [0, 0, 2e5, 0, 0, 0]}
  - {id: k2, at: [3.4, 0.2, 0.1], axial: 1e6, direction: [0, 0, 1]}
supports:
  - {plane: [[0, 0, 0], [0, 0, 1]], dofs: all}
)";

Eigen::VectorXd modes10(const fe::Model& m) { return test::checked_modal_analysis(m, 10).result.frequencies_hz(); }

void expect_same_modes(const fe::Model& a, const fe::Model& b, double tol) {
  const Eigen::VectorXd fa = modes10(a), fb = modes10(b);
  ASSERT_EQ(fa.size(), fb.size());
  double worst = 0;
  for (Eigen::Index k = 0; k < fa.size(); ++k) {
    EXPECT_NEAR(fb(k) / fa(k), 1.0, tol) << "mode " << k + 1;
    worst = std::max(worst, std::abs(fb(k) / fa(k) - 1.0));
  }
  std::printf("deck round trip: worst of ten modes %.2e\n", worst);
}

// Each beam split in two at its midpoint, as a B32R written and read back is.
fe::Model split_beams(fe::Model m) {
  std::vector<fe::BeamElement> beams;
  for (const fe::BeamElement& b : m.beams) {
    const fe::NodeId mid = m.add_node(m.next_node_id(), 0.5 * (m.position(b.nodes[0]) + m.position(b.nodes[1])));
    fe::BeamElement first = b, second = b;
    first.id += ".1";
    second.id += ".2";
    first.nodes = {b.nodes[0], mid};
    second.nodes = {mid, b.nodes[1]};
    beams.push_back(first);
    beams.push_back(second);
  }
  m.beams = beams;
  return m;
}

TEST(ModelExport, ADeckReadBackGivesTheSameModes) {
  const io::ModelFile m = io::parse_model(kMixed + "}" + kRest, "mixed.yaml");
  io::CalculixOptions o;
  o.heading = "mixed";
  const io::ModelFile back = io::parse_abaqus_deck(io::calculix_input(m.model, o), "mixed.inp");
  EXPECT_EQ(back.model.shells.size(), m.model.shells.size());
  EXPECT_EQ(back.model.solids.size(), m.model.solids.size());
  EXPECT_EQ(back.model.beams.size(), 2 * m.model.beams.size());
  expect_same_modes(split_beams(m.model), back.model, 1e-9);
}

TEST(ModelExport, ForAbaqusCirclesTakeTheRadiusAndMassesKeepTheirRotaryInertia) {
  const io::ModelFile m = io::parse_model(kMixed + ", inertia: [0.3, 0.2, 0.1, 0.01, 0, 0]}" + kRest, "mixed.yaml");
  io::CalculixOptions o;
  EXPECT_THROW(io::calculix_input(m.model, o), std::invalid_argument);  // ccx 2.20: no rotary inertia
  o.dialect = io::CalculixDialect::abaqus;
  const std::string deck = io::calculix_input(m.model, o);
  EXPECT_NE(deck.find("SECTION=CIRC\n0.02\n"), std::string::npos);  // the radius alone
  EXPECT_NE(deck.find("*ROTARY INERTIA"), std::string::npos);
  const io::ModelFile back = io::parse_abaqus_deck(deck, "mixed.inp");
  ASSERT_EQ(back.model.point_masses.size(), 1u);
  EXPECT_EQ(back.model.point_masses[0].inertia, m.model.point_masses[0].inertia);
  expect_same_modes(split_beams(m.model), back.model, 1e-9);
}

// A Craig-Bampton reduction with all three matrices.
reduction::ReducedFrame reduced() {
  fe::Model model = io::parse_model(kMixed + "}" + kRest, "mixed.yaml").model;
  model.solids.clear();  // the pad is a separate body; keep the frame
  model.springs.pop_back();
  reduction::FrameReductionOptions o;
  o.interface_set = "joints";
  o.method = reduction::ReductionMethod::craig_bampton;
  o.modes = 6;
  std::vector<fe::NodeId> corners;
  for (const fe::Node& n : model.nodes)
    if (n.x.z() > 1.49 && (n.x.x() < 1e-9 || n.x.x() > 1 - 1e-9) && (n.x.y() < 1e-9 || n.x.y() > 0.4 - 1e-9))
      corners.push_back(n.id);
  model.node_sets["joints"] = corners;
  model.point_masses.clear();
  return reduction::reduce_frame(model, o);
}

// (id, component) -> index in the reduced coordinates, as the exports number them.
std::map<std::pair<long, int>, Eigen::Index> numbering(const reduction::ReducedFrame& r, int modal_component) {
  std::map<std::pair<long, int>, Eigen::Index> at;
  Eigen::Index k = 0;
  for (const auto& d : r.interface_dofs) at[{d.node, d.local + 1}] = k++;
  for (int j = 0; j < r.mode_count; ++j) at[{io::modal_coordinate_base(r) + j, modal_component}] = k++;
  return at;
}

std::string field(const std::string& line, size_t start, size_t width) {
  std::string f = line.size() > start ? line.substr(start, width) : "";
  f.erase(0, f.find_first_not_of(' '));
  f.erase(f.find_last_not_of(' ') + 1);
  return f;
}

// The DMIG matrices of the text, filled symmetric from the one entry per pair.
std::map<std::string, Eigen::MatrixXd> parse_dmig(const std::string& text, const reduction::ReducedFrame& r) {
  const auto at = numbering(r, 0);
  const auto n = r.K.rows();
  std::map<std::string, Eigen::MatrixXd> out;
  std::map<std::string, std::set<std::pair<Eigen::Index, Eigen::Index>>> seen;
  std::istringstream in(text);
  std::string line, name;
  Eigen::Index column = -1;
  while (std::getline(in, line)) {
    if (line.rfind("DMIG*", 0) == 0) {
      name = field(line, 8, 16);
      column = at.at({std::stol(field(line, 24, 16)), std::stoi(field(line, 40, 16))});
    } else if (line.rfind("DMIG", 0) == 0) {
      EXPECT_EQ(field(line, 16, 8), "0");
      EXPECT_EQ(field(line, 24, 8), "6");  // symmetric
      EXPECT_EQ(field(line, 32, 8), "2");  // real double
      out[field(line, 8, 8)] = Eigen::MatrixXd::Zero(n, n);
    } else if (line.rfind("*", 0) == 0) {
      const Eigen::Index row = at.at({std::stol(field(line, 8, 16)), std::stoi(field(line, 24, 16))});
      std::string v = field(line, 40, 16);
      std::replace(v.begin(), v.end(), 'D', 'E');
      EXPECT_TRUE(seen[name].insert({std::min(row, column), std::max(row, column)}).second) << "pair given twice";
      out[name](row, column) = out[name](column, row) = std::stod(v);
    }
  }
  return out;
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(ModelExport, DmigCardsHoldTheReducedMatrices) {
  const reduction::ReducedFrame r = reduced();
  ASSERT_GT(r.mode_count, 0);
  const std::string text = io::nastran_dmig(r);
  EXPECT_NE(text.find("SPOINT  " + std::to_string(io::modal_coordinate_base(r))), std::string::npos);
  const auto m = parse_dmig(text, r);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_LT(relative(m.at("KAAX"), r.K), 1e-9);
  EXPECT_LT(relative(m.at("MAAX"), r.M), 1e-9);
  EXPECT_LT(relative(m.at("BAAX"), r.C), 1e-9);
}

TEST(ModelExport, AbaqusMatrixFilesHoldTheReducedMatricesExactly) {
  const reduction::ReducedFrame r = reduced();
  const auto files = io::abaqus_matrix_files(r, "frame");
  ASSERT_EQ(files.size(), 4u);
  const std::string& inp = files.at("frame.inp");
  EXPECT_NE(inp.find("*MATRIX INPUT, NAME=frame-K, INPUT=frame_K.txt"), std::string::npos);
  EXPECT_NE(inp.find("*MATRIX ASSEMBLE, STIFFNESS=frame-K, MASS=frame-M, VISCOUS DAMPING=frame-C"), std::string::npos);
  EXPECT_NE(inp.find(std::to_string(io::modal_coordinate_base(r)) + ", "), std::string::npos);  // the modal nodes
  const auto at = numbering(r, 1);
  for (const auto& [file, original] : {std::pair<std::string, const Eigen::MatrixXd*>{"frame_K.txt", &r.K},
                                       {"frame_M.txt", &r.M},
                                       {"frame_C.txt", &r.C}}) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(r.K.rows(), r.K.cols());
    std::istringstream in(files.at(file));
    std::string line;
    while (std::getline(in, line)) {
      long ni = 0, nj = 0;
      int di = 0, dj = 0;
      double v = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "%ld, %d, %ld, %d, %lf", &ni, &di, &nj, &dj, &v), 5) << line;
      const Eigen::Index i = at.at({ni, di}), j = at.at({nj, dj});
      EXPECT_GE(i, j) << "lower triangle";
      A(i, j) = A(j, i) = v;
    }
    EXPECT_EQ(relative(A, *original), 0.0) << file;
  }
}

}  // namespace
}  // namespace rigflex
