#include "reduction/frame_reduction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "fe/assembly.hpp"
#include "fe/dof.hpp"
#include "fe/error.hpp"
#include "fe/mass_properties.hpp"
#include "linalg/pencil_scale.hpp"
#include "reduction/rayleigh_damping.hpp"
#include "reduction/reduction_checks.hpp"
#include "reduction/state_space.hpp"

namespace rigflex::reduction {
namespace {

// An eigenvalue below this fraction of the pencil's scale (pencil_scale: the
// mass-weighted mean of K_ii / M_ii, ~ the upper spectrum) is a rigid-body
// mode. Computed rigid-body eigenvalues sit at rounding level, ~1e-14 of
// that scale; the first elastic mode of a frame meshed finely enough to be
// worth reducing lies above ~1e-8 of it.
constexpr double kRigidFraction = 1e-10;
// Reduced eigenvalues closer than this (relative) form one cluster for the
// subspace MAC: symmetric frames have pairs the two models split differently.
constexpr double kClusterTolerance = 1e-6;

void report(const FrameReductionOptions& o, const std::string& stage) {
  if (o.progress) o.progress(stage);
}

// A model is held by its supports, or by a superelement that was reduced
// with its own supports (it holds the model through its stiffness).
bool held_by_model(const fe::Model& model) {
  return !model.supports.empty() || std::any_of(model.superelements.begin(), model.superelements.end(),
                                                [](const fe::Superelement& e) { return e.grounded; });
}

FrameSupport resolve_support(const fe::Model& model, const FrameReductionOptions& o) {
  const bool held = held_by_model(model);
  FrameSupport s = o.support.value_or(o.reference_node ? FrameSupport::reference_node
                                      : held           ? FrameSupport::grounded
                                                       : FrameSupport::free);
  if (s == FrameSupport::grounded && !held) {
    throw std::invalid_argument(
        "support: a grounded reduction needs supports (or a grounded superelement), and the "
        "model has none (use a free or reference-node reduction for a floating frame)");
  }
  if (s != FrameSupport::grounded && held) {
    throw std::invalid_argument(std::string("support: a ") + to_string(s) +
                                " reduction is for a floating frame, but the model is held by " +
                                (model.supports.empty() ? std::string("a grounded superelement")
                                                        : std::to_string(model.supports.size()) + " supports"));
  }
  return s;
}

// A reference-node reduction holds that node: a copy of the model with the
// node supported. The other supports reduce the model as it is.
std::optional<fe::Model> held_copy(const fe::Model& model, FrameSupport s, const FrameReductionOptions& o) {
  if (s != FrameSupport::reference_node) return std::nullopt;
  if (!model.has_node(*o.reference_node)) {
    throw fe::ModelError({"node", std::to_string(*o.reference_node), "reference_node"},
                         "reference node " + std::to_string(*o.reference_node) + " is not in the model");
  }
  fe::Model m = model;
  m.supports.push_back({"reference-node", *o.reference_node, fe::DofMask{true, true, true, true, true, true}});
  return m;
}

std::vector<InterfaceNode> interface_nodes(const fe::Model& model, const FrameReductionOptions& o) {
  const std::vector<fe::NodeId> ids = model.node_set(o.interface_set);  // throws if missing
  if (ids.empty()) {
    throw fe::ModelError({"node_set", o.interface_set, ""}, "interface node set '" + o.interface_set + "' is empty");
  }
  std::vector<InterfaceNode> nodes;
  for (fe::NodeId id : ids) {
    if (!model.has_node(id)) {
      throw fe::ModelError({"node_set", o.interface_set, ""}, "interface node set '" + o.interface_set +
                                                                  "' names node " + std::to_string(id) +
                                                                  ", which is not in the model");
    }
    if (std::any_of(nodes.begin(), nodes.end(), [&](const InterfaceNode& n) { return n.id == id; })) {
      throw fe::ModelError({"node_set", o.interface_set, ""}, "interface node set '" + o.interface_set +
                                                                  "' lists node " + std::to_string(id) + " twice");
    }
    if (o.reference_node && *o.reference_node == id) {
      throw fe::ModelError({"node_set", o.interface_set, ""},
                           "the reference node " + std::to_string(id) + " is held, so it cannot be an interface node");
    }
    nodes.push_back({id, model.position(id)});
  }
  return nodes;
}

// Free-DOF columns of the interface DOFs. A DOF a support holds is left out
// (it does not move); any other DOF that is not free is an error.
std::vector<Eigen::Index> interface_columns(const fe::Model& model, const fe::DofMap& dofs,
                                            const std::vector<InterfaceNode>& nodes, const FrameReductionOptions& o,
                                            std::vector<InterfaceDof>& order) {
  std::map<fe::NodeId, fe::DofMask> held;
  for (const fe::Support& s : model.supports)
    for (size_t d = 0; d < 6; ++d) held[s.node][d] = held[s.node][d] || s.fixed[d];
  for (const auto& chosen : o.node_dofs) {
    const fe::NodeId id = chosen.first;
    if (std::none_of(nodes.begin(), nodes.end(), [&](const InterfaceNode& n) { return n.id == id; }))
      throw fe::ModelError({"node_set", o.interface_set, ""}, "DOFs are chosen for node " + std::to_string(id) +
                                                                  ", which is not in the interface set '" +
                                                                  o.interface_set + "'");
  }
  std::vector<Eigen::Index> cols;
  const int per_node = o.retained == InterfaceDofs::all ? 6 : 3;
  for (const auto& n : nodes) {
    const auto chosen = o.node_dofs.find(n.id);
    size_t kept = 0;
    for (int d = 0; d < 6; ++d) {
      const bool wanted = chosen != o.node_dofs.end() ? chosen->second[static_cast<size_t>(d)] : d < per_node;
      if (!wanted) continue;
      if (d >= per_node)
        throw fe::ModelError({"node_set", o.interface_set, ""},
                             "node " + std::to_string(n.id) + " " + std::string(fe::dof_name(d)) +
                                 ": a rotation is retained only with retained DOFs 'all'");
      const auto h = held.find(n.id);
      if (h != held.end() && h->second[static_cast<size_t>(d)]) continue;  // held: it does not move
      const long col = dofs.full_to_free[model.node_index(n.id) * fe::kDofsPerNode + static_cast<size_t>(d)];
      if (col < 0) {
        throw fe::ModelError({"node_set", o.interface_set, ""},
                             "interface DOF node " + std::to_string(n.id) + " " + std::string(fe::dof_name(d)) +
                                 " is not a free DOF: it is driven by a coupling (a rigid coupling's dependent or a "
                                 "distributing coupling's reference), or carries neither stiffness nor mass");
      }
      cols.push_back(col);
      order.push_back({n.id, d});
      ++kept;
    }
    if (kept == 0)
      throw fe::ModelError({"node_set", o.interface_set, ""},
                           "interface node " + std::to_string(n.id) + " keeps no DOF (all chosen DOFs are held)");
  }
  return cols;
}

struct FullModes {
  linalg::EigenResult result;
  int rigid = 0;  // leading rigid-body modes
};

FullModes full_model_modes(const fe::AssembledSystem& sys, FrameSupport support, const FrameReductionOptions& o) {
  const int expected_rigid = support == FrameSupport::free ? 6 : 0;
  const int needed = std::max(o.check_modes, std::max(o.zeta_modes[0], o.zeta_modes[1]));
  const Eigen::Index n = sys.K.rows();
  if (expected_rigid + std::max(o.zeta_modes[0], o.zeta_modes[1]) > n) {
    throw std::invalid_argument("zeta modes: mode " + std::to_string(std::max(o.zeta_modes[0], o.zeta_modes[1])) +
                                " does not exist; the model has " + std::to_string(n - expected_rigid) +
                                " elastic modes");
  }
  linalg::EigenOptions eo;
  eo.count = static_cast<int>(std::min<Eigen::Index>(n, expected_rigid + needed));
  eo.max_factor_bytes = o.max_factor_bytes;
  eo.analyzed = o.analyzed;
  FullModes f;
  f.result = o.eigen_backend ? o.eigen_backend(sys.K, sys.M, eo) : solve_lanczos(sys.K, sys.M, eo);
  if (f.result.over_memory_limit) {
    ReductionError e("full-model modes: " + f.result.message);
    e.over_memory_limit = true;
    throw e;
  }
  if (!f.result.mechanism_dofs.empty()) {
    std::vector<std::string> names;
    for (Eigen::Index d : f.result.mechanism_dofs) names.push_back(sys.dofs.describe(d));
    throw ReductionError("the model is a mechanism: K - sigma M is singular", names);
  }
  if (!f.result.converged) throw ReductionError("full-model modes: " + f.result.message);
  const double rigid_limit = kRigidFraction * linalg::pencil_scale(sys.K, sys.M);
  while (f.rigid < f.result.eigenvalues.size() && f.result.eigenvalues(f.rigid) < rigid_limit) ++f.rigid;
  return f;
}

void frequency_checks(const FullModes& full, const linalg::EigenResult& reduced, const Eigen::MatrixXd& expanded,
                      double rigid_limit_reduced, ReductionChecks& c) {
  const Eigen::VectorXd fh = full.result.frequencies_hz();
  const Eigen::VectorXd rh = reduced.frequencies_hz();
  c.mac = mac_matrix(full.result.vectors, expanded);
  const Eigen::Index rows = std::min(fh.size(), rh.size());
  for (Eigen::Index k = 0; k < rows; ++k) {
    FrequencyCheck f;
    f.mode = static_cast<int>(k + 1);
    f.full_hz = fh(k);
    f.reduced_hz = rh(k);
    const bool rigid = k < full.rigid;
    f.error_percent = rigid || fh(k) <= 0 ? 0.0 : 100.0 * (rh(k) - fh(k)) / fh(k);
    // The cluster of reduced modes around mode k: all rigid-body modes, or
    // those with (nearly) the same eigenvalue.
    std::vector<Eigen::Index> cluster;
    const double lk = reduced.eigenvalues(k);
    for (Eigen::Index j = 0; j < reduced.eigenvalues.size(); ++j) {
      const double lj = reduced.eigenvalues(j);
      const bool both_rigid = lk < rigid_limit_reduced && lj < rigid_limit_reduced;
      if (both_rigid || std::abs(lj - lk) <= kClusterTolerance * std::max(std::abs(lk), std::abs(lj))) {
        cluster.push_back(j);
      }
    }
    Eigen::MatrixXd B(expanded.rows(), static_cast<Eigen::Index>(cluster.size()));
    for (size_t j = 0; j < cluster.size(); ++j) B.col(static_cast<Eigen::Index>(j)) = expanded.col(cluster[j]);
    f.mac = subspace_mac(full.result.vectors.col(k), B);
    Eigen::Index best = 0;
    f.matched_mac = c.mac.row(k).maxCoeff(&best);
    f.matched_mode = static_cast<int>(best + 1);
    c.frequencies.push_back(f);
  }
}

}  // namespace

void FrameReductionOptions::validate() const {
  if (interface_set.empty()) throw std::invalid_argument("interface: the name of a node set is required");
  if (!(zeta > 0 && zeta < 1)) {
    throw std::invalid_argument("zeta: the damping ratio must lie in (0, 1), got " + std::to_string(zeta));
  }
  for (int m : zeta_modes) {
    if (m < 1) throw std::invalid_argument("zeta modes: mode numbers start at 1, got " + std::to_string(m));
  }
  if (zeta_modes[0] == zeta_modes[1]) throw std::invalid_argument("zeta modes: give two different modes");
  if (check_modes < 1) throw std::invalid_argument("check modes: must be >= 1");
  if (reference_node && support && *support != FrameSupport::reference_node) {
    throw std::invalid_argument("reference node: given with a " + std::string(to_string(*support)) + " reduction");
  }
  if (support == FrameSupport::reference_node && !reference_node) {
    throw std::invalid_argument("reference node: a reference-node reduction needs the node to hold");
  }
  ComponentModeOptions c;
  c.method = method;
  c.modes = modes;
  c.cutoff_hz = cutoff_hz;
  c.validate(std::numeric_limits<Eigen::Index>::max());
}

namespace {

// Rayleigh damping from the full model's elastic modes o.zeta_modes, the
// damping matrix (rigid motions of a free frame left undamped) and the
// state-space form.
void add_damping(const FullModes& full, const FrameReductionOptions& o, const Eigen::MatrixXd& rigid, ReducedFrame& r) {
  const int elastic = static_cast<int>(full.result.eigenvalues.size()) - full.rigid;
  for (int m : o.zeta_modes) {
    if (m > elastic) {
      throw std::invalid_argument("zeta modes: elastic mode " + std::to_string(m) + " does not exist; the model has " +
                                  std::to_string(elastic) + " elastic modes");
    }
  }
  std::array<double, 2> omega{};
  for (int k = 0; k < 2; ++k) {
    omega[k] = std::sqrt(full.result.eigenvalues(full.rigid + o.zeta_modes[k] - 1));
  }
  r.damping = rayleigh_coefficients(o.zeta_modes, omega, {o.zeta, o.zeta});
  const bool floating_free = r.support == FrameSupport::free;
  r.C = rayleigh_damping_matrix(r.K, r.M, r.damping, floating_free ? rigid : Eigen::MatrixXd());
  r.state_space = state_space_form(r.K, r.M, r.C, r.interface_dof_count(), floating_free ? rigid : Eigen::MatrixXd());
}

// The reduction against the full model: frequencies and MAC, damping
// ratios, rigid-body modes, mass properties and static exactness at the
// interface.
ReductionChecks reduction_checks(const fe::Model& model, const fe::AssembledSystem& sys,
                                 const std::vector<Eigen::Index>& boundary, const FullModes& full,
                                 const Eigen::MatrixXd& basis, const Eigen::MatrixXd& rigid, const ReducedFrame& r) {
  const bool floating_free = r.support == FrameSupport::free;
  ReductionChecks c;
  const double scale_r = r.K.trace() / r.M.trace();
  const linalg::EigenResult reduced =
      linalg::solve_dense(r.K, r.M, static_cast<int>(r.K.rows()), -kRigidFraction * std::max(scale_r, 1.0));
  const double rigid_limit_r = kRigidFraction * scale_r;
  c.reduced_frequencies_hz = reduced.frequencies_hz();
  c.damping_ratios.resize(reduced.eigenvalues.size());
  for (Eigen::Index k = 0; k < reduced.eigenvalues.size(); ++k) {
    const double lk = reduced.eigenvalues(k);
    if (lk < rigid_limit_r) {
      ++c.rigid_body_modes_reduced;
      c.damping_ratios(k) = 0.0;
    } else {
      const Eigen::VectorXd& v = reduced.vectors.col(k);
      c.damping_ratios(k) = v.dot(r.C * v) / (2 * std::sqrt(lk));
    }
  }
  c.rigid_body_modes_full = full.rigid;
  const Eigen::MatrixXd expanded = basis * reduced.vectors;
  frequency_checks(full, reduced, expanded, rigid_limit_r, c);

  c.mass_full = fe::mass_properties(model);
  const Eigen::Matrix<double, 6, 6> Mrb = rigid.transpose() * r.M * rigid;
  c.mass_reduced = fe::mass_properties_from_rigid_mass(Mrb);
  c.mass_comparable = floating_free;
  if (floating_free) {
    const double knorm = r.K.cwiseAbs().colwise().sum().maxCoeff();
    for (Eigen::Index k = 0; k < 6; ++k) {
      const double rn = rigid.col(k).norm();
      c.rigid_body_residual = std::max(c.rigid_body_residual, (r.K * rigid.col(k)).norm() / (knorm * rn));
    }
  }

  // Static exactness: unit loads at the interface, full vs reduced; a
  // floating frame is held isostatically at six interface DOFs.
  std::vector<Eigen::Index> held_rows;
  if (floating_free) {
    held_rows = isostatic_rows(rigid.topRows(r.interface_dof_count()));
    for (Eigen::Index h : held_rows) c.static_support.push_back(r.interface_dofs[static_cast<size_t>(h)]);
  }
  std::vector<Eigen::Index> held_full, reduced_boundary;
  for (Eigen::Index h : held_rows) held_full.push_back(boundary[static_cast<size_t>(h)]);
  for (Eigen::Index k = 0; k < r.interface_dof_count(); ++k) reduced_boundary.push_back(k);
  const Eigen::MatrixXd Gf = full_interface_flexibility(sys.K, boundary, held_full);
  const Eigen::MatrixXd Gr = reduced_interface_flexibility(r.K, reduced_boundary, held_rows);
  c.static_flexibility_error = (Gr - Gf).cwiseAbs().maxCoeff() / Gf.cwiseAbs().maxCoeff();
  return c;
}

}  // namespace

ReducedFrame reduce_frame(const fe::Model& model, const FrameReductionOptions& o) {
  o.validate();
  ReducedFrame r;
  r.method = o.method;
  r.retained = o.retained;
  r.interface_set = o.interface_set;
  r.support = resolve_support(model, o);
  if (r.support == FrameSupport::reference_node) r.reference_node = o.reference_node;
  r.interface_nodes = interface_nodes(model, o);
  const std::optional<fe::Model> copy = held_copy(model, r.support, o);
  const fe::Model& held = copy ? *copy : model;

  report(o, "assembling");
  fe::AssemblyOptions ao;
  ao.progress = o.assembly_progress;
  const fe::AssembledSystem sys = fe::assemble(held, ao);
  const std::vector<Eigen::Index> boundary = interface_columns(held, sys.dofs, r.interface_nodes, o, r.interface_dofs);
  r.full_free_dofs = sys.dofs.free_count();

  report(o, std::string("reducing (") + to_string(o.method) + ")");
  ComponentModeOptions co;
  co.method = o.method;
  co.modes = o.modes;
  co.cutoff_hz = o.cutoff_hz;
  co.max_factor_bytes = o.max_factor_bytes;
  co.analyzed = o.analyzed;
  co.eigen_backend = o.eigen_backend;
  ReducedMatrices red = reduce_component(sys.K, sys.M, boundary, co);
  if (!red.ok) {
    std::vector<std::string> names;
    for (Eigen::Index d : red.mechanism_dofs) names.push_back(sys.dofs.describe(d));
    ReductionError e(red.message, names);
    e.over_memory_limit = red.over_memory_limit;
    throw e;
  }
  r.K = std::move(red.K);
  r.M = std::move(red.M);
  r.mode_count = static_cast<int>(red.mode_eigenvalues.size());
  r.mode_frequencies_hz = red.mode_eigenvalues.cwiseMax(0.0).cwiseSqrt() / (2 * M_PI);

  report(o, "full-model modes for damping and checks");
  const FullModes full = full_model_modes(sys, r.support, o);
  const Eigen::MatrixXd rigid = interface_rigid_motions(r.interface_nodes, r.interface_dofs, r.K.rows());
  add_damping(full, o, rigid, r);
  report(o, "checks");
  r.checks = reduction_checks(model, sys, boundary, full, red.basis, rigid, r);
  return r;
}

}  // namespace rigflex::reduction
