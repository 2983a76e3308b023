#include "io/reduced_export.hpp"

#include <charconv>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fe/dof.hpp"
#include "io/matrix_market.hpp"
#include "io/mass_record.hpp"
#include "io/reduced_layout.hpp"
#include "io/reduced_mat.hpp"

namespace rigflex::io {
namespace {

using nlohmann::ordered_json;
using reduction::ReducedFrame;
namespace layout = reduced_layout;

// Node ids up to this travel exactly through the doubles of reduced.mat.
constexpr long kLargestExactId = 1L << 53;

[[noreturn]] void refuse_export(const std::string& what) { throw std::invalid_argument("reduced frame export: " + what); }

std::string size_text(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

void require_size(const Eigen::MatrixXd& A, layout::MatrixSize size, const std::string& name, const std::string& why) {
  if (A.rows() != size.rows || A.cols() != size.cols)
    refuse_export(name + " is " + size_text(A.rows(), A.cols()) + ", expected " + size_text(size.rows, size.cols) + " (" +
           why + ")");
}

void require_finite(const Eigen::MatrixXd& A, const std::string& name) {
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      if (!std::isfinite(A(i, j)))
        refuse_export(name + "(" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ") is " + number_text(A(i, j)));
}

void require_finite(const ordered_json& j, const std::string& path) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    refuse_export(path + " is " + number_text(j.get<double>()) + ", which JSON cannot hold");
  if (j.is_object())
    for (const auto& [key, value] : j.items()) require_finite(value, path.empty() ? key : path + "." + key);
  if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) require_finite(j[i], path + "[" + std::to_string(i) + "]");
}

void check_structure(const ReducedFrame& r) {
  const bool needs_reference = r.support == reduction::FrameSupport::reference_node;
  if (needs_reference != r.reference_node.has_value())
    refuse_export(needs_reference ? "support 'reference-node' without a reference node"
                           : std::string("a reference node with support '") + to_string(r.support) + "'");
  std::set<fe::NodeId> nodes;
  for (const auto& n : r.interface_nodes) {
    if (!nodes.insert(n.id).second) refuse_export("interface node " + std::to_string(n.id) + " listed twice");
    if (n.id > kLargestExactId || n.id < -kLargestExactId)
      refuse_export("interface node id " + std::to_string(n.id) + " is beyond 2^53, which reduced.mat cannot hold exactly");
  }
  std::set<std::pair<fe::NodeId, int>> dofs;
  for (const auto& d : r.interface_dofs) {
    if (!nodes.count(d.node)) refuse_export("interface DOF of node " + std::to_string(d.node) + ", which is not an interface node");
    if (d.local < 0 || d.local >= fe::kDofsPerNode)
      refuse_export("interface DOF " + std::to_string(d.local) + " of node " + std::to_string(d.node) + " is not in 0..5");
    if (!dofs.insert({d.node, d.local}).second)
      refuse_export("interface DOF " + std::string(fe::dof_name(d.local)) + " of node " + std::to_string(d.node) +
             " listed twice");
  }
  // Each node keeps some of its DOFs (those chosen, less those a support holds).
  const int per_node = r.retained == reduction::InterfaceDofs::translations ? 3 : 6;
  for (const auto& d : r.interface_dofs)
    if (d.local >= per_node)
      refuse_export("interface DOF " + std::string(fe::dof_name(d.local)) + " of node " + std::to_string(d.node) +
                    " with retained DOFs '" + to_string(r.retained) + "'");
  std::set<fe::NodeId> kept;
  for (const auto& d : r.interface_dofs) kept.insert(d.node);
  if (kept.size() != nodes.size()) refuse_export("an interface node keeps no DOF");
  for (const auto& d : r.checks.static_support)
    if (d.local < 0 || d.local >= fe::kDofsPerNode)
      refuse_export("static_support DOF " + std::to_string(d.local) + " of node " + std::to_string(d.node) + " is not in 0..5");
  if (r.mode_count < 0) refuse_export("negative mode count");
  if (r.mode_frequencies_hz.size() != r.mode_count)
    refuse_export(std::to_string(r.mode_frequencies_hz.size()) + " mode frequencies for " + std::to_string(r.mode_count) +
           " modes");
  if (r.full_free_dofs < 0) refuse_export("negative full_free_dofs");
  if (r.checks.damping_ratios.size() != r.checks.reduced_frequencies_hz.size())
    refuse_export(std::to_string(r.checks.damping_ratios.size()) + " damping ratios for " +
           std::to_string(r.checks.reduced_frequencies_hz.size()) + " reduced frequencies");

  const Eigen::Index m = r.interface_dof_count();
  const Eigen::Index n = m + r.mode_count;
  const auto& ss = r.state_space;
  const bool modal = ss.coordinates == reduction::StateCoordinates::modal;
  if (ss.rigid_body_modes < 0 || ss.rigid_body_modes > n || (!modal && ss.rigid_body_modes != 0))
    refuse_export("state space with " + std::to_string(ss.rigid_body_modes) + " rigid-body modes in " +
                  to_string(ss.coordinates) + " coordinates");
  const std::string why = std::to_string(m) + " interface DOFs + " + std::to_string(r.mode_count) + " modes";
  for (const auto& f : layout::kMatrixFiles) {
    const Eigen::MatrixXd& A = layout::matrix(r, f.key);
    require_size(A, layout::matrix_size(f.key, n, m), f.key, why);
    require_finite(A, f.key);
  }
}

ordered_json numbers(const Eigen::VectorXd& v) {
  ordered_json out = ordered_json::array();
  for (const double x : v) out.push_back(x);
  return out;
}

ordered_json dof_json(const reduction::InterfaceDof& d) {
  return {{"node", d.node}, {"dof", std::string(fe::dof_name(d.local))}};
}

ordered_json checks_json(const reduction::ReductionChecks& c) {
  ordered_json frequencies = ordered_json::array();
  for (const auto& f : c.frequencies)
    frequencies.push_back({{"mode", f.mode},
                           {"full_hz", f.full_hz},
                           {"reduced_hz", f.reduced_hz},
                           {"error_percent", f.error_percent},
                           {"mac", f.mac},
                           {"matched_mode", f.matched_mode},
                           {"matched_mac", f.matched_mac}});
  ordered_json mac = ordered_json::array();
  for (Eigen::Index i = 0; i < c.mac.rows(); ++i) mac.push_back(numbers(c.mac.row(i).transpose()));
  ordered_json support = ordered_json::array();
  for (const auto& d : c.static_support) support.push_back(dof_json(d));
  return {{"frequencies", frequencies},
          {"mac", mac},
          {"rigid_body_modes",
           {{"full", c.rigid_body_modes_full}, {"reduced", c.rigid_body_modes_reduced}, {"residual", c.rigid_body_residual}}},
          {"mass_properties",
           {{"comparable", c.mass_comparable},
            {"full", ordered_json(mass_properties_json(c.mass_full))},
            {"reduced", ordered_json(mass_properties_json(c.mass_reduced))}}},
          {"static_flexibility", {{"error", c.static_flexibility_error}, {"support", support}}},
          {"reduced_frequencies_hz", numbers(c.reduced_frequencies_hz)},
          {"damping_ratios", numbers(c.damping_ratios)}};
}

// Checks `r` and returns reduced.json's text.
std::string reduced_json_text(const ReducedFrame& r) {
  check_structure(r);
  const ordered_json j = reduced_frame_json(r);
  require_finite(j, "");
  try {
    return j.dump(2) + "\n";
  } catch (const nlohmann::json::type_error&) {
    refuse_export("the name or the interface set name is not valid UTF-8");
  }
}

}  // namespace

void check_exportable(const ReducedFrame& r) { reduced_json_text(r); }

nlohmann::ordered_json reduced_frame_json(const ReducedFrame& r) {
  ordered_json nodes = ordered_json::array();
  for (const auto& n : r.interface_nodes)
    nodes.push_back({{"id", n.id}, {"position", {n.position.x(), n.position.y(), n.position.z()}}});
  ordered_json dofs = ordered_json::array();
  for (const auto& d : r.interface_dofs) dofs.push_back(dof_json(d));
  const auto& damping = r.damping;
  ordered_json files = ordered_json::object();
  for (const auto& f : layout::kMatrixFiles) files[f.key] = f.file;
  files[layout::kMatKey] = layout::kMatFile;
  const Eigen::Index m = r.interface_dof_count();
  const Eigen::Index n = m + r.mode_count;

  ordered_json j;
  j["format"] = kReducedFrameFormat;
  j["version"] = kReducedFrameVersion;
  j["name"] = r.name;
  j["method"] = to_string(r.method);
  j["units"] = layout::units_json();
  j["support"] = to_string(r.support);
  j["reference_node"] = r.reference_node ? ordered_json(*r.reference_node) : ordered_json(nullptr);
  j["retained_dofs"] = to_string(r.retained);
  j["interface_set"] = r.interface_set;
  j["interface_nodes"] = nodes;
  j["dof_order"] = dofs;
  j["mode_count"] = r.mode_count;
  j["mode_frequencies_hz"] = numbers(r.mode_frequencies_hz);
  j["coordinate_count"] = n;
  j["full_free_dofs"] = r.full_free_dofs;
  j["damping"] = {{"type", "rayleigh"},
                  {"modes", {damping.modes[0], damping.modes[1]}},
                  {"zeta", {damping.zeta[0], damping.zeta[1]}},
                  {"omega", {damping.omega[0], damping.omega[1]}},
                  {"alpha", damping.alpha},
                  {"beta", damping.beta}};
  j["state_space"] = {{"states", 2 * n},
                      {"inputs", m},
                      {"outputs", 2 * m},
                      {"coordinates", to_string(r.state_space.coordinates)},
                      {"rigid_body_modes", r.state_space.rigid_body_modes}};
  j["checks"] = checks_json(r.checks);
  j["files"] = files;
  return j;
}

void add_reduced_frame_files(FileBatch& batch, const std::filesystem::path& dir, const ReducedFrame& r) {
  // Everything that can fail is done before the first file joins the batch.
  std::string json = reduced_json_text(r);
  std::vector<std::pair<std::string, std::string>> matrices;
  for (const auto& f : layout::kMatrixFiles)
    matrices.emplace_back(f.file, matrix_market_text(layout::matrix(r, f.key),
                                                     "rigflex reduced frame '" + r.name + "': " + f.what));
  add_reduced_mat_file(batch, dir / layout::kMatFile, r);
  for (auto& [file, text] : matrices) batch.add_text(dir / file, std::move(text));
  batch.add_text(dir / layout::kJsonFile, std::move(json));
}

void write_reduced_frame(const std::filesystem::path& dir, const ReducedFrame& r) {
  FileBatch batch;
  add_reduced_frame_files(batch, dir, r);
  batch.commit();
}

}  // namespace rigflex::io
