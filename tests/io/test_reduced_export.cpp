// Exports of a reduced frame: every file reads back bit for bit; malformed
// files name the file, the line and the key; nothing is left half-written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <set>

#include "support/awkward_doubles.hpp"
#include "support/input_errors.hpp"
#include "support/temp_files.hpp"
#include "support/text_edits.hpp"
#include "io/input_error.hpp"
#include "io/json_fields.hpp"
#include "io/matrix_market.hpp"
#include "io/reduced_export.hpp"
#include "io/reduced_mat.hpp"

namespace rigflex {
namespace {

using test::replace_first;
using test::line_of;

namespace fs = std::filesystem;
using reduction::ReducedFrame;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test::read_text;
using test::write_text;

std::set<std::string> files_below(const fs::path& dir) {
  std::set<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) out.insert(fs::relative(e.path(), dir).string());
  return out;
}

// Craig-Bampton, floating on a reference node, all six DOFs of three nodes,
// three modes; every number awkward.
ReducedFrame awkward_frame() {
  test::AwkwardDoubles a;
  ReducedFrame r;
  r.name = "awkward \"frame\"\twith \xc3\xbc";
  r.method = reduction::ReductionMethod::craig_bampton;
  r.support = reduction::FrameSupport::reference_node;
  r.reference_node = 123456789012345L;
  r.retained = reduction::InterfaceDofs::all;
  r.interface_set = "upper_joints";
  r.interface_nodes = {{7, {1.0 / 3, -0.0, 1e-300}}, {1L << 53, a.vec3()}, {-4, a.vec3()}};
  for (const auto& n : r.interface_nodes)
    for (int d = 0; d < 6; ++d) r.interface_dofs.push_back({n.id, d});
  r.mode_count = 3;
  r.mode_frequencies_hz = Eigen::Vector3d(1.0 / 3, std::numeric_limits<double>::denorm_min(), 1e308);
  const Eigen::Index m = 18, n = 21;
  r.K = a.matrix(n, n);
  r.K(0, 0) = -0.0;
  r.K(1, 0) = std::numeric_limits<double>::denorm_min();
  r.K(0, 1) = 1e-300;
  r.K(2, 2) = std::numeric_limits<double>::max();
  r.M = a.matrix(n, n);
  r.M(0, 0) = 1.0 / 3;
  r.C = a.matrix(n, n);
  r.state_space.A = a.matrix(2 * n, 2 * n);
  r.state_space.B = a.matrix(2 * n, m);
  r.state_space.C = a.matrix(2 * m, 2 * n);
  r.state_space.D = a.matrix(2 * m, m);
  r.state_space.T = a.matrix(n, n);
  r.state_space.coordinates = reduction::StateCoordinates::modal;
  r.state_space.rigid_body_modes = 6;
  r.damping = {{2, 5}, {0.02, 1.0 / 3}, {a.next(), a.next()}, a.next(), -0.0};
  for (int k = 1; k <= 4; ++k) {
    reduction::FrequencyCheck f{k, a.next(), a.next(), a.next(), a.next()};
    f.matched_mode = 5 - k;
    f.matched_mac = a.next();
    r.checks.frequencies.push_back(f);
  }
  r.checks.mac = a.matrix(4, 5);
  r.checks.rigid_body_modes_full = 6;
  r.checks.rigid_body_modes_reduced = 5;
  r.checks.rigid_body_residual = 1e-300;
  r.checks.mass_full = a.mass();
  r.checks.mass_reduced = a.mass();
  r.checks.mass_comparable = true;
  r.checks.static_flexibility_error = a.next();
  for (int d = 0; d < 3; ++d) r.checks.static_support.push_back({7, d});
  for (int d = 3; d < 6; ++d) r.checks.static_support.push_back({-4, d});
  r.checks.reduced_frequencies_hz = a.vector(n);
  r.checks.damping_ratios = a.vector(n);
  r.full_free_dofs = 123456789012L;
  return r;
}

// Guyan onto translations of a grounded frame: no modes, no reference node,
// empty checks.
ReducedFrame plain_frame() {
  test::AwkwardDoubles a;
  ReducedFrame r;
  r.name = "plain";
  r.interface_set = "joints";
  r.interface_nodes = {{1, a.vec3()}, {2, a.vec3()}};
  for (const auto& n : r.interface_nodes)
    for (int d = 0; d < 3; ++d) r.interface_dofs.push_back({n.id, d});
  r.K = a.matrix(6, 6);
  r.M = a.matrix(6, 6);
  r.C = a.matrix(6, 6);
  r.state_space = {a.matrix(12, 12), a.matrix(12, 6), a.matrix(12, 12), a.matrix(12, 6), a.matrix(6, 6)};
  r.full_free_dofs = 600;
  return r;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

void expect_same(double a, double b, const std::string& what) {
  EXPECT_TRUE(same_bits(a, b)) << what << ": " << a << " read back as " << b;
}

void expect_same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  if (a.size() > 0) {
    EXPECT_EQ(std::memcmp(a.data(), b.data(), static_cast<size_t>(a.size()) * sizeof(double)), 0) << what;
  }
}

void expect_same(const fe::MassProperties& a, const fe::MassProperties& b, const std::string& what) {
  expect_same(a.mass, b.mass, what + ".mass");
  expect_same(a.cog, b.cog, what + ".cog");
  expect_same(a.inertia, b.inertia, what + ".inertia");
}

void expect_same(const std::vector<reduction::InterfaceDof>& a, const std::vector<reduction::InterfaceDof>& b,
                 const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].node, b[i].node) << what << " " << i;
    EXPECT_EQ(a[i].local, b[i].local) << what << " " << i;
  }
}

void expect_same(const ReducedFrame& a, const ReducedFrame& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.support, b.support);
  EXPECT_EQ(a.reference_node, b.reference_node);
  EXPECT_EQ(a.retained, b.retained);
  EXPECT_EQ(a.interface_set, b.interface_set);
  ASSERT_EQ(a.interface_nodes.size(), b.interface_nodes.size());
  for (size_t i = 0; i < a.interface_nodes.size(); ++i) {
    EXPECT_EQ(a.interface_nodes[i].id, b.interface_nodes[i].id);
    expect_same(a.interface_nodes[i].position, b.interface_nodes[i].position, "interface node position");
  }
  expect_same(a.interface_dofs, b.interface_dofs, "interface_dofs");
  EXPECT_EQ(a.mode_count, b.mode_count);
  expect_same(a.mode_frequencies_hz, b.mode_frequencies_hz, "mode_frequencies_hz");
  expect_same(a.K, b.K, "K");
  expect_same(a.M, b.M, "M");
  expect_same(a.C, b.C, "C");
  EXPECT_EQ(a.damping.modes, b.damping.modes);
  for (int k = 0; k < 2; ++k) {
    expect_same(a.damping.zeta[k], b.damping.zeta[k], "damping.zeta");
    expect_same(a.damping.omega[k], b.damping.omega[k], "damping.omega");
  }
  expect_same(a.damping.alpha, b.damping.alpha, "damping.alpha");
  expect_same(a.damping.beta, b.damping.beta, "damping.beta");
  expect_same(a.state_space.A, b.state_space.A, "state_space.A");
  expect_same(a.state_space.B, b.state_space.B, "state_space.B");
  expect_same(a.state_space.C, b.state_space.C, "state_space.C");
  expect_same(a.state_space.D, b.state_space.D, "state_space.D");
  expect_same(a.state_space.T, b.state_space.T, "state_space.T");
  EXPECT_EQ(a.state_space.coordinates, b.state_space.coordinates);
  EXPECT_EQ(a.state_space.rigid_body_modes, b.state_space.rigid_body_modes);
  const auto& ca = a.checks;
  const auto& cb = b.checks;
  ASSERT_EQ(ca.frequencies.size(), cb.frequencies.size());
  for (size_t i = 0; i < ca.frequencies.size(); ++i) {
    EXPECT_EQ(ca.frequencies[i].mode, cb.frequencies[i].mode);
    expect_same(ca.frequencies[i].full_hz, cb.frequencies[i].full_hz, "full_hz");
    expect_same(ca.frequencies[i].reduced_hz, cb.frequencies[i].reduced_hz, "reduced_hz");
    expect_same(ca.frequencies[i].error_percent, cb.frequencies[i].error_percent, "error_percent");
    expect_same(ca.frequencies[i].mac, cb.frequencies[i].mac, "frequencies.mac");
    EXPECT_EQ(ca.frequencies[i].matched_mode, cb.frequencies[i].matched_mode);
    expect_same(ca.frequencies[i].matched_mac, cb.frequencies[i].matched_mac, "frequencies.matched_mac");
  }
  expect_same(ca.mac, cb.mac, "checks.mac");
  EXPECT_EQ(ca.rigid_body_modes_full, cb.rigid_body_modes_full);
  EXPECT_EQ(ca.rigid_body_modes_reduced, cb.rigid_body_modes_reduced);
  expect_same(ca.rigid_body_residual, cb.rigid_body_residual, "rigid_body_residual");
  expect_same(ca.mass_full, cb.mass_full, "mass_full");
  expect_same(ca.mass_reduced, cb.mass_reduced, "mass_reduced");
  EXPECT_EQ(ca.mass_comparable, cb.mass_comparable);
  expect_same(ca.static_flexibility_error, cb.static_flexibility_error, "static_flexibility_error");
  expect_same(ca.static_support, cb.static_support, "static_support");
  expect_same(ca.reduced_frequencies_hz, cb.reduced_frequencies_hz, "reduced_frequencies_hz");
  expect_same(ca.damping_ratios, cb.damping_ratios, "damping_ratios");
  EXPECT_EQ(a.full_free_dofs, b.full_free_dofs);
}

const std::set<std::string> kExportFiles = {"reduced.json", "reduced.mat", "K.mtx",    "M.mtx",    "C.mtx",
                                            "ss_A.mtx",     "ss_B.mtx",    "ss_C.mtx", "ss_D.mtx", "ss_T.mtx"};

// ---------------------------------------------------------------- Matrix Market

io::InputError mm_error(const std::string& text, const std::optional<io::MatrixShape>& expected = std::nullopt) {
  return test::input_error_of([&] { io::parse_matrix_market(text, "bad.mtx", expected); }, "the text:\n" + text);
}

void expect_error(const io::InputError& e, int line, const std::string& words) {
  EXPECT_EQ(e.line(), line) << e.what();
  EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
}

TEST(MatrixMarket, RoundTripIsBitExact) {
  test::AwkwardDoubles a;
  Eigen::MatrixXd A = a.matrix(9, 7);
  A(0, 0) = -0.0;
  A(1, 0) = std::numeric_limits<double>::denorm_min();
  A(2, 0) = 1e-300;
  A(3, 0) = std::numeric_limits<double>::max();
  A(4, 0) = std::numeric_limits<double>::lowest();
  A(5, 0) = 1.0 / 3;
  const std::string text = io::matrix_market_text(A, "what it is\nsecond line");
  EXPECT_EQ(text.rfind("%%MatrixMarket matrix array real general\n% what it is\n% second line\n9 7\n-0\n", 0), 0u)
      << text.substr(0, 120);
  const Eigen::MatrixXd B = io::parse_matrix_market(text, "a.mtx");
  expect_same(A, B, "A");
  EXPECT_TRUE(std::signbit(B(0, 0)));
  for (const Eigen::MatrixXd& C : {Eigen::MatrixXd(0, 3), Eigen::MatrixXd(1, 1), a.matrix(1, 5), a.matrix(5, 1)})
    expect_same(C, io::parse_matrix_market(io::matrix_market_text(C, ""), "c.mtx"), "small");
}

TEST(MatrixMarket, WriterRefusesNaNAndInfinity) {
  test::TempDir dir("rigflex-export");
  for (const double bad : {kNaN, kInf, -kInf}) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Ones(3, 4);
    A(1, 2) = bad;
    try {
      io::matrix_market_text(A, "");
      ADD_FAILURE() << "no error for " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("entry (2, 3)"), std::string::npos) << e.what();
    }
    EXPECT_THROW(io::write_matrix_market(dir.path() / "A.mtx", A, "a"), std::invalid_argument);
    EXPECT_TRUE(files_below(dir.path()).empty());
  }
}

TEST(MatrixMarket, ReadsCoordinateSymmetricAndIntegerFiles) {
  Eigen::MatrixXd expected(3, 2);
  expected << 1.5, 0, 0, 0, 0, -2e-3;
  expect_same(expected,
              io::parse_matrix_market("%%MatrixMarket matrix coordinate real general\n% c\n\n3 2 2\n1 1 1.5\n3 2 -2e-3\n",
                                      "c.mtx"),
              "coordinate general");

  Eigen::MatrixXd sym(3, 3);
  sym << 1, 2, 0, 2, 0, 3, 0, 3, 4;
  expect_same(sym,
              io::parse_matrix_market("%%MatrixMarket matrix coordinate real symmetric\n3 3 4\n1 1 1\n2 1 2\n3 2 3\n3 3 4\n",
                                      "s.mtx"),
              "coordinate symmetric");
  expect_same(sym, io::parse_matrix_market("%%MATRIXMARKET Matrix Array Integer Symmetric\n3 3\n1\n2\n0\n0\n+3\n4\n", "i.mtx"),
              "array integer symmetric");

  Eigen::MatrixXd skew(3, 3);
  skew << 0, -5, -6, 5, 0, -7, 6, 7, 0;
  expect_same(skew, io::parse_matrix_market("%%MatrixMarket matrix array real skew-symmetric\n3 3\n5\n6 7\n", "k.mtx"),
              "array skew-symmetric");
  expect_same(skew,
              io::parse_matrix_market("%%MatrixMarket matrix coordinate integer skew-symmetric\n3 3 3\n2 1 5\n3 1 6\n3 2 7\n",
                                      "k.mtx"),
              "coordinate skew-symmetric");
}

TEST(MatrixMarket, MalformedFilesNameTheLine) {
  const std::string array = "%%MatrixMarket matrix array real general\n% c\n2 2\n";
  EXPECT_EQ(mm_error("hello\n").file(), "bad.mtx");
  expect_error(mm_error(""), 1, "empty file");
  expect_error(mm_error("hello\n2 2\n"), 1, "%%MatrixMarket");
  expect_error(mm_error("%%MatrixMarket matrix array complex general\n1 1\n1 0\n"), 1, "complex");
  expect_error(mm_error("%%MatrixMarket matrix coordinate pattern general\n1 1 1\n1 1\n"), 1, "pattern");
  expect_error(mm_error("%%MatrixMarket matrix array real general\n"), 1, "no size line");
  expect_error(mm_error("%%MatrixMarket matrix array real general\n% c\n2 x\n"), 3, "'x'");
  expect_error(mm_error("%%MatrixMarket matrix array real symmetric\n2 3\n"), 2, "square");
  expect_error(mm_error(array + "1\n2\nabc\n4\n"), 6, "'abc' is not a number");
  expect_error(mm_error(array + "1\n2\n3\n"), 6, "only 3 of the 4");
  expect_error(mm_error(array + "1\n2\n3\n4\n5\n"), 8, "more values");
  expect_error(mm_error(array + "1\nnan\n3\n4\n"), 5, "not finite");
  expect_error(mm_error(array + "1\n1e999\n3\n4\n"), 5, "range of a double");
  expect_error(mm_error("%%MatrixMarket matrix array integer general\n1 1\n1.5\n"), 3, "not an integer");
  const std::string coordinate = "%%MatrixMarket matrix coordinate real general\n2 2 2\n";
  expect_error(mm_error(coordinate + "1 1 1\n3 1 1\n"), 4, "outside the 2 x 2");
  expect_error(mm_error(coordinate + "1 1 1\n1 1 2\n"), 4, "given twice");
  expect_error(mm_error(coordinate + "1 1 1\n2 2\n"), 4, "'row column value'");
  expect_error(mm_error(coordinate + "1 1 1\n"), 3, "only 1 of the 2");
  expect_error(mm_error(coordinate + "1 1 1\n2 2 1\n1 2 1\n"), 5, "more entries");
  expect_error(mm_error("%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n"), 3, "above the diagonal");
  expect_error(mm_error(array + "1\n2\n3\n4\n", io::MatrixShape{3, 3, "from the test"}), 3,
               "2 x 2 but 3 x 3 is expected (from the test)");
  // An empty matrix of a billion columns: nothing to allocate, but each
  // column was walked (47 s under the sanitizers; found by fuzzing).
  expect_error(mm_error("%%MatrixMarket matrix array real general\n0 1328787907\n"), 2,
               "more than 1000000 rows or columns");
  expect_error(mm_error("%%MatrixMarket matrix array real general\n20000 20000\n"), 2, "too large for a dense");
}

TEST(MatrixMarket, ReadsTheFileItWrote) {
  test::TempDir dir("rigflex-export");
  const Eigen::MatrixXd A = test::AwkwardDoubles().matrix(4, 3);
  io::write_matrix_market(dir.path() / "A.mtx", A, "A");
  expect_same(A, io::read_matrix_market(dir.path() / "A.mtx"), "A");
  EXPECT_EQ(files_below(dir.path()), std::set<std::string>{"A.mtx"});
  try {
    io::read_matrix_market(dir.path() / "missing.mtx");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "missing.mtx").string());
  }
}

// ---------------------------------------------------------------- JSON lines

TEST(JsonFields, NamesTheLineAndPathOfEveryValue) {
  const std::string text = "{\n  \"a\": 1,\n  \"b\": [\n    2,\n    3.5\n  ],\n  \"c\": {\"d\": true}\n}\n";
  const io::JsonFields f(text, "x.json");
  EXPECT_EQ(f.line_of("a"), 2);
  EXPECT_EQ(f.line_of("b"), 3);
  EXPECT_EQ(f.line_of("b[1]"), 5);
  EXPECT_EQ(f.line_of("c.d"), 7);
  const auto b = f.elements(f.required(f.root(), "b"));
  try {
    f.integer(b[1]);
    ADD_FAILURE() << "3.5 read as an integer";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.key(), "b[1]");
  }
  try {
    io::JsonFields("{\n  \"a\": 1,\n  \"b\": ]\n}\n", "y.json");
    ADD_FAILURE() << "malformed JSON accepted";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "y.json");
    EXPECT_EQ(e.line(), 3);
  }
}

// ---------------------------------------------------------------- reduced frame

TEST(ReducedExport, RoundTripIsBitExact) {
  test::TempDir dir("rigflex-export");
  const ReducedFrame r = awkward_frame();
  io::write_reduced_frame(dir.path(), r);
  EXPECT_EQ(files_below(dir.path()), kExportFiles);
  const ReducedFrame back = io::read_reduced_frame(dir.path());
  expect_same(r, back);
  EXPECT_TRUE(std::signbit(back.interface_nodes[0].position.y()));
  EXPECT_TRUE(std::signbit(back.K(0, 0)));
  EXPECT_TRUE(std::signbit(back.damping.beta));
  // Writing what was read gives the same bytes: nothing lost, nothing dated.
  io::write_reduced_frame(dir.path() / "again", back);
  for (const auto& name : kExportFiles)
    EXPECT_TRUE(read_text(dir.path() / name) == read_text(dir.path() / "again" / name)) << name;
}

TEST(ReducedExport, RoundTripOfAGuyanFrameWithoutModes) {
  test::TempDir dir("rigflex-export");
  const ReducedFrame r = plain_frame();
  io::write_reduced_frame(dir.path(), r);
  expect_same(r, io::read_reduced_frame(dir.path()));
  const io::ReducedMatVariables v = io::read_reduced_mat(dir.path() / "reduced.mat");
  EXPECT_EQ(v.mode_frequencies_hz.size(), 0);
  expect_same(r.K, v.K, "K");
}

TEST(ReducedExport, JsonHoldsTheDocumentedRecords) {
  test::TempDir dir("rigflex-export");
  const ReducedFrame r = awkward_frame();
  io::write_reduced_frame(dir.path(), r);
  const auto j = nlohmann::json::parse(read_text(dir.path() / "reduced.json"));
  EXPECT_EQ(j["format"], "rigflex-reduced-frame");
  EXPECT_EQ(j["version"], 2);
  EXPECT_EQ(j["method"], "craig-bampton");
  EXPECT_EQ(j["support"], "reference-node");
  EXPECT_EQ(j["retained_dofs"], "all");
  EXPECT_EQ(j["units"]["length"], "m");
  EXPECT_EQ(j["dof_order"][0], (nlohmann::json{{"node", 7}, {"dof", "UX"}}));
  EXPECT_EQ(j["dof_order"][17], (nlohmann::json{{"node", -4}, {"dof", "RZ"}}));
  EXPECT_EQ(j["coordinate_count"], 21);
  EXPECT_EQ(j["state_space"],
            (nlohmann::json{
                {"states", 42}, {"inputs", 18}, {"outputs", 36}, {"coordinates", "modal"}, {"rigid_body_modes", 6}}));
  const auto& full = j["checks"]["mass_properties"]["full"];
  EXPECT_EQ(full["inertia"].size(), 6u);
  EXPECT_EQ(full["inertia"][3].get<double>(), r.checks.mass_full.inertia(0, 1));  // Jxy
  EXPECT_EQ(full["inertia"][5].get<double>(), r.checks.mass_full.inertia(1, 2));  // Jyz
  std::set<std::string> listed = {"reduced.json"};
  for (const auto& [key, name] : j["files"].items()) listed.insert(name.get<std::string>());
  EXPECT_EQ(listed, kExportFiles);
  const std::string k = read_text(dir.path() / "K.mtx");
  EXPECT_EQ(k.rfind("%%MatrixMarket matrix array real general\n% rigflex reduced frame 'awkward", 0), 0u);
}

TEST(ReducedExport, MatFileReadsBackBitExact) {
  test::TempDir dir("rigflex-export");
  const ReducedFrame r = awkward_frame();
  io::write_reduced_frame(dir.path(), r);
  EXPECT_EQ(read_text(dir.path() / "reduced.mat").rfind("MATLAB 5.0 MAT-file", 0), 0u);
  const io::ReducedMatVariables v = io::read_reduced_mat(dir.path() / "reduced.mat");
  expect_same(r.K, v.K, "K");
  expect_same(r.M, v.M, "M");
  expect_same(r.C, v.C, "C");
  expect_same(r.state_space.A, v.A, "A");
  expect_same(r.state_space.B, v.B, "B");
  expect_same(r.state_space.C, v.Css, "Css");
  expect_same(r.state_space.D, v.D, "D");
  expect_same(r.state_space.T, v.T, "T");
  ASSERT_EQ(v.interface_nodes.size(), 3);
  ASSERT_EQ(v.interface_coordinates.rows(), 3);
  ASSERT_EQ(v.interface_coordinates.cols(), 3);
  for (Eigen::Index i = 0; i < 3; ++i) {
    const auto& node = r.interface_nodes[static_cast<size_t>(i)];
    EXPECT_EQ(v.interface_nodes(i), static_cast<double>(node.id));
    expect_same(node.position.transpose(), v.interface_coordinates.row(i), "interface_coordinates");
  }
  EXPECT_EQ(v.interface_nodes(1), 9007199254740992.0);  // 2^53, exact
  ASSERT_EQ(v.dof_node.size(), 18);
  ASSERT_EQ(v.dof_index.size(), 18);
  for (Eigen::Index i = 0; i < 18; ++i) {
    const auto& dof = r.interface_dofs[static_cast<size_t>(i)];
    EXPECT_EQ(v.dof_node(i), static_cast<double>(dof.node));
    EXPECT_EQ(v.dof_index(i), dof.local + 1.0);
  }
  expect_same(r.damping.alpha, v.alpha, "alpha");
  expect_same(r.damping.beta, v.beta, "beta");
  expect_same(r.mode_frequencies_hz, v.mode_frequencies_hz, "mode_frequencies_hz");
}

io::InputError mat_error(const fs::path& file) {
  return test::input_error_of([&] { io::read_reduced_mat(file); }, file.string());
}

TEST(ReducedExport, MatReaderRefusesWhatIsNotAReducedFrame) {
  test::TempDir dir("rigflex-export");
  const fs::path file = dir.path() / "x.mat";
  write_text(file, "not a MAT file at all, but long enough to have a header of 128 bytes........................"
                   ".......................................................................................");
  EXPECT_EQ(mat_error(file).file(), file.string());
  EXPECT_NE(std::string(mat_error(file).what()).find("not a MAT file"), std::string::npos);
  EXPECT_NE(std::string(mat_error(dir.path() / "none.mat").what()).find("cannot open"), std::string::npos);

  const io::ReducedMatVariables good = io::reduced_mat_variables(awkward_frame());
  auto with = [&](auto change) {
    io::ReducedMatVariables v = good;
    change(v);
    io::write_reduced_mat(file, v);
    return mat_error(file);
  };
  EXPECT_EQ(with([](auto& v) { v.dof_index(3) = 7; }).key(), "dof_index");
  EXPECT_EQ(with([](auto& v) { v.dof_node(3) = 8; }).key(), "dof_node");
  EXPECT_EQ(with([](auto& v) { v.Css.conservativeResize(v.Css.rows() - 1, Eigen::NoChange); }).key(), "Css");
  EXPECT_EQ(with([](auto& v) { v.interface_coordinates.conservativeResize(Eigen::NoChange, 2); }).key(),
            "interface_coordinates");
  EXPECT_EQ(with([](auto& v) { v.mode_frequencies_hz.conservativeResize(2); }).key(), "mode_frequencies_hz");
  EXPECT_EQ(with([](auto& v) { v.M.conservativeResize(20, 21); }).key(), "M");

  // A file cut short anywhere, even inside the data of its last variable, is
  // refused (matio alone would fill the missing bytes with whatever).
  io::write_reduced_mat(file, good);
  const std::string bytes = read_text(file);
  for (size_t length = 0; length < bytes.size(); length += 1 + length / 8) {
    write_text(file, bytes.substr(0, length));
    EXPECT_EQ(mat_error(file).file(), file.string()) << "cut at " << length << " of " << bytes.size();
  }
  write_text(file, bytes.substr(0, bytes.size() - 1));
  EXPECT_EQ(mat_error(file).file(), file.string()) << "cut by one byte";
}

TEST(ReducedExport, WriterRefusesWhatItCannotWriteExactly) {
  test::TempDir dir("rigflex-export");
  const fs::path out = dir.path() / "out";
  auto refusal = [&](auto change) -> std::string {
    ReducedFrame r = awkward_frame();
    change(r);
    io::FileBatch batch;
    try {
      io::add_reduced_frame_files(batch, out, r);
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      batch.commit();  // whatever was added before the error would appear now
      EXPECT_FALSE(fs::exists(out));
      return e.what();
    }
    return "";
  };
  EXPECT_NE(refusal([](ReducedFrame& r) { r.K(3, 4) = kNaN; }).find("K(4, 5)"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.state_space.B(0, 0) = kInf; }).find("ss_B(1, 1)"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.checks.mac(1, 2) = kNaN; }).find("checks.mac[1][2]"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.checks.mass_full.cog.y() = kInf; }).find("checks.mass_properties.full.cog[1]"),
            std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.M.conservativeResize(20, 20); }).find("M is 20 x 20"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.mode_count = 2; }).find("mode frequencies"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.support = reduction::FrameSupport::free; }).find("reference node"),
            std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.interface_dofs[4].node = 99; }).find("node 99"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.interface_dofs[4].local = 3; }).find("twice"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.interface_nodes[2].id = (1L << 53) + 1; }).find("2^53"), std::string::npos);
  EXPECT_NE(refusal([](ReducedFrame& r) { r.name = "bad \xff"; }).find("UTF-8"), std::string::npos);
}

TEST(ReducedExport, AFailingBatchLeavesNoFileBehind) {
  test::TempDir dir("rigflex-export");
  const fs::path out = dir.path() / "out";
  {
    io::FileBatch batch;
    io::add_reduced_frame_files(batch, out, awkward_frame());
    EXPECT_TRUE(files_below(out).empty()) << "files written before commit";
    batch.add(out / "later.txt", [](const fs::path&) { throw std::runtime_error("disk full"); });
    EXPECT_THROW(batch.commit(), std::runtime_error);
    EXPECT_TRUE(files_below(out).empty());
  }
  // An earlier export survives a failed one untouched.
  const ReducedFrame first = plain_frame();
  io::write_reduced_frame(out, first);
  io::FileBatch batch;
  io::add_reduced_frame_files(batch, out, awkward_frame());
  batch.add(out / "later.txt", [](const fs::path&) { throw std::runtime_error("disk full"); });
  EXPECT_THROW(batch.commit(), std::runtime_error);
  EXPECT_EQ(files_below(out), kExportFiles);
  expect_same(first, io::read_reduced_frame(out));
}

// ---------------------------------------------------------------- reader errors

class ReducedImport : public ::testing::Test {
 protected:
  void SetUp() override {
    io::write_reduced_frame(dir_.path(), awkward_frame());
    json_ = read_text(json_path());
  }
  fs::path json_path() const { return dir_.path() / "reduced.json"; }

  // Reads the export with reduced.json replaced by `text`.
  io::InputError error_with_json(const std::string& text) {
    write_text(json_path(), text);
    return error();
  }
  io::InputError error() {
    try {
      io::read_reduced_frame(dir_.path());
    } catch (const io::InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error";
    return io::InputError("", 0, "", "");
  }
  // reduced.json with one value changed (re-dumped like the writer does).
  std::string json_with(const std::function<void(nlohmann::ordered_json&)>& change) const {
    auto j = nlohmann::ordered_json::parse(json_);
    change(j);
    return j.dump(2) + "\n";
  }

  test::TempDir dir_{"rigflex-export"};
  std::string json_;
};

TEST_F(ReducedImport, MissingKeyNamesFileLineAndKey) {
  const auto e = error_with_json(json_with([](auto& j) { j["checks"]["rigid_body_modes"].erase("residual"); }));
  EXPECT_EQ(e.file(), json_path().string());
  EXPECT_EQ(e.key(), "checks.rigid_body_modes.residual");
  EXPECT_EQ(e.line(), line_of(json_, "\"rigid_body_modes\": {"));  // the checks one, not the state space's count
  EXPECT_EQ(error_with_json(json_with([](auto& j) { j.erase("mode_count"); })).key(), "mode_count");
}

TEST_F(ReducedImport, WrongValuesNameTheirLine) {
  struct Case {
    std::function<void(nlohmann::ordered_json&)> change;
    std::string key, needle, words;
  };
  const Case cases[] = {
      {[](auto& j) { j["checks"]["rigid_body_modes"]["full"] = "six"; }, "checks.rigid_body_modes.full",
       "\"full\": \"six\"", "expected an integer"},
      {[](auto& j) { j["method"] = "gyan"; }, "method", "\"gyan\"", "craig-bampton"},
      {[](auto& j) { j["format"] = "something-else"; }, "format", "something-else", "rigflex-reduced-frame"},
      {[](auto& j) {
         j["version"] = 3;
         j["new_in_version_3"] = true;
       },
       "version", "\"version\": 3", "version 3"},
      {[](auto& j) { j["state_space"]["coordinates"] = "polar"; }, "state_space.coordinates", "\"polar\"",
       "physical, modal"},
      {[](auto& j) { j["state_space"]["rigid_body_modes"] = 22; }, "state_space.rigid_body_modes",
       "\"rigid_body_modes\": 22", "expected 0 to 21"},
      {[](auto& j) { j["state_space"]["coordinates"] = "physical"; }, "state_space.rigid_body_modes",
       "\"rigid_body_modes\": 6", "must be 0 with physical"},
      {[](auto& j) { j["dof_order"][3]["node"] = 99; }, "dof_order[3].node", "\"node\": 99", "not in interface_nodes"},
      {[](auto& j) { j["dof_order"][3]["dof"] = "UW"; }, "dof_order[3].dof", "\"UW\"", "UX, UY"},
      {[](auto& j) { j["checks"]["damping_ratios"][2] = nullptr; }, "checks.damping_ratios[2]", "null", "null"},
      {[](auto& j) { j["files"]["K"] = "../K.mtx"; }, "files.K", "../K.mtx", "plain file name"},
      {[](auto& j) { j["coordinate_count"] = 22; }, "coordinate_count", "\"coordinate_count\": 22", "expected 21"},
      {[](auto& j) { j["reference_node"] = nullptr; }, "reference_node", "\"reference_node\": null", "reference node"},
      {[](auto& j) { j["units"]["length"] = "mm"; }, "units", "\"units\"", "SI"},
      {[](auto& j) { j["state_space"]["inputs"] = 17; }, "state_space.inputs", "\"inputs\": 17", "expected 18"},
      {[](auto& j) { j["damping"]["zeta"].push_back(0.1); }, "damping.zeta", "\"zeta\"", "expected 2 values"},
      {[](auto& j) { j["checks"]["mac"][2].erase(0); }, "checks.mac[2]", "\"mac\": [", "expected 5 values"},
      {[](auto& j) { j["extra"] = 1; }, "extra", "\"extra\"", "unknown key"},
  };
  for (const auto& c : cases) {
    const std::string text = json_with(c.change);
    const auto e = error_with_json(text);
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_EQ(e.file(), json_path().string());
    // A needle that occurs earlier than the value is harmless: then the
    // expected line is only a lower bound, and must still be reached.
    if (c.key == "checks.mac[2]") EXPECT_GT(e.line(), line_of(text, "\"mac\": [")) << e.what();
    else if (c.key == "damping.zeta") EXPECT_EQ(e.line(), line_of(text, "\"zeta\"")) << e.what();
    else EXPECT_EQ(e.line(), line_of(text, c.needle)) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << e.what();
  }
}

// A folder written before the state space named its coordinates (version
// 1: no ss_T.mtx, no state_space.coordinates) reads as physical, T = I.
TEST_F(ReducedImport, VersionOneFolderReadsWithPhysicalCoordinates) {
  write_text(json_path(), json_with([](auto& j) {
               j["version"] = 1;
               j["state_space"].erase("coordinates");
               j["state_space"].erase("rigid_body_modes");
               j["files"].erase("ss_T");
             }));
  fs::remove(dir_.path() / "ss_T.mtx");
  const ReducedFrame r = io::read_reduced_frame(dir_.path());
  EXPECT_EQ(r.state_space.coordinates, reduction::StateCoordinates::physical);
  EXPECT_EQ(r.state_space.rigid_body_modes, 0);
  EXPECT_EQ(r.state_space.T, Eigen::MatrixXd::Identity(21, 21));
  expect_same(awkward_frame().state_space.A, r.state_space.A, "state_space.A");
  // A version 1 file with the version 2 keys is not a version 1 file.
  const auto e = error_with_json(json_with([](auto& j) { j["version"] = 1; }));
  EXPECT_EQ(e.key(), "state_space.coordinates") << e.what();
  EXPECT_NE(std::string(e.what()).find("unknown key"), std::string::npos) << e.what();
}

TEST_F(ReducedImport, MalformedJsonNamesTheLine) {
  const std::string text = replace_first(json_, "\"mode_count\": 3,", "\"mode_count\": 3,,");
  const auto e = error_with_json(text);
  EXPECT_EQ(e.line(), line_of(text, "\"mode_count\""));
  EXPECT_NE(std::string(e.what()).find("malformed JSON"), std::string::npos);
}

TEST_F(ReducedImport, MatrixFilesMustMatchTheJson) {
  const fs::path k = dir_.path() / "K.mtx";
  write_text(k, io::matrix_market_text(Eigen::MatrixXd::Ones(20, 20), "one comment line"));
  auto e = error();
  EXPECT_EQ(e.file(), k.string());
  EXPECT_EQ(e.line(), 3);  // the size line
  EXPECT_NE(std::string(e.what()).find("20 x 20 but 21 x 21 is expected (18 interface DOFs + 3 modes"),
            std::string::npos)
      << e.what();
}

TEST_F(ReducedImport, MalformedMatrixFilesNameFileAndLine) {
  const fs::path m = dir_.path() / "M.mtx";
  std::string text = read_text(m);
  const int size_line = line_of(text, "\n21 21\n") + 1;
  // The tenth value of M, on the tenth line after the size line.
  size_t at = 0;
  for (int line = 1; line < size_line + 10; ++line) at = text.find('\n', at) + 1;
  text.insert(at, "x");
  write_text(m, text);
  auto e = error();
  EXPECT_EQ(e.file(), m.string());
  EXPECT_EQ(e.line(), size_line + 10);
  EXPECT_NE(std::string(e.what()).find("is not a number"), std::string::npos) << e.what();

  const fs::path c = dir_.path() / "C.mtx";
  write_text(c, replace_first(read_text(c), "array real general", "array real hermitian"));
  fs::copy_file(dir_.path() / "K.mtx", m, fs::copy_options::overwrite_existing);
  e = error();
  EXPECT_EQ(e.file(), c.string());
  EXPECT_EQ(e.line(), 1);

  fs::copy_file(dir_.path() / "K.mtx", c, fs::copy_options::overwrite_existing);
  fs::remove(dir_.path() / "ss_D.mtx");
  e = error();
  EXPECT_EQ(e.file(), (dir_.path() / "ss_D.mtx").string());
  EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace rigflex
