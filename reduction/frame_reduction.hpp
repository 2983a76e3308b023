#pragma once
// Reduction of a frame model onto the DOFs of a named node set of joint
// centres, with Rayleigh damping, state-space form and the checks that ship
// with every reduction (reduced_model.hpp).
#include <array>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fe/model.hpp"
#include "reduction/component_modes.hpp"
#include "reduction/reduced_model.hpp"

namespace rigflex::reduction {

struct FrameReductionOptions {
  std::string interface_set;  // node set naming the joint centres (required)
  InterfaceDofs retained = InterfaceDofs::translations;
  // Per node, the DOFs retained instead of `retained` (nodes of the
  // interface set only; at least one DOF each; translations only when
  // `retained` is translations, as the exported files say).
  std::map<fe::NodeId, fe::DofMask> node_dofs;
  ReductionMethod method = ReductionMethod::guyan;
  int modes = 0;                    // Craig-Bampton mode count ...
  std::optional<double> cutoff_hz;  // ... or cutoff
  // nullopt: grounded when the model has supports, free-free otherwise.
  std::optional<FrameSupport> support;
  std::optional<fe::NodeId> reference_node;  // FrameSupport::reference_node
  double zeta = 0.02;
  std::array<int, 2> zeta_modes{1, 3};  // 1-based elastic modes of the full model
  int check_modes = 10;                 // elastic modes of the full model compared
  std::function<void(const std::string&)> progress;  // optional stage messages
  std::function<void(long done, long total)> assembly_progress;  // optional: elements assembled (fe::AssemblyOptions)
  // Each factorization (the interior K_ii, the full model's for the checks)
  // is analyzed first and not attempted past max_factor_bytes (0: no
  // limit): ReductionError with over_memory_limit. `analyzed` (optional)
  // hears each analysis before its numeric work.
  double max_factor_bytes = 0;
  std::function<void(const linalg::FactorStatistics&)> analyzed;
  // The eigen solver of the full model's modes and Craig-Bampton's
  // fixed-interface modes (empty: the built-in Lanczos; the MPI backend of
  // linalg/slepc_eigen.hpp with its vectors gathered on every rank, since
  // the checks use them). The constraint modes stay with CHOLMOD.
  linalg::EigenBackend eigen_backend;

  // Throws std::invalid_argument naming the option: zeta outside (0, 1), mode
  // indices < 1 or equal, check_modes < 1, reference_node without that
  // support, and the ComponentModeOptions rules.
  void validate() const;
};

// Throws fe::ModelError for an invalid model or an interface set that is
// missing, empty, or names a node that is not in the model or whose DOF is
// dependent or unused. An interface DOF that a support holds is left out of
// the interface (a partly supported interface node keeps its free DOFs);
// a node with no DOF left is an error; std::invalid_argument for invalid options, for a
// grounded reduction of a model without supports (or a free one with
// supports) and for mode indices beyond what the model has. Numerical
// failures (a mechanism, no convergence) throw ReductionError with the free
// DOFs named.
ReducedFrame reduce_frame(const fe::Model& model, const FrameReductionOptions& options);

struct ReductionError : std::runtime_error {
  std::vector<std::string> free_dofs;  // "node 12 RZ", for a mechanism
  bool over_memory_limit = false;      // a factor past FrameReductionOptions::max_factor_bytes
  ReductionError(const std::string& what, std::vector<std::string> dofs = {})
      : std::runtime_error(what), free_dofs(std::move(dofs)) {}
};

}  // namespace rigflex::reduction
