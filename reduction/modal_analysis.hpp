#pragma once
// A modal analysis of a frame model: assemble, solve, summarize.
#include <string>

#include "fe/assembly.hpp"
#include "fe/mass_properties.hpp"
#include "fe/model.hpp"
#include "linalg/eigen_solver.hpp"
#include "reduction/modal_summary.hpp"

namespace rigflex::reduction {

struct ModalAnalysis {
  fe::AssembledSystem system;
  fe::MassProperties mass;  // of the whole model
  linalg::EigenResult result;
  ModalSummary summary;
  // Filled when K - sigma M was singular: "node 12 RZ", ...
  std::vector<std::string> mechanism;
};

// Never throws for numerical outcomes: check result.converged and mechanism.
// Throws fe::ModelError for an invalid model and std::invalid_argument for
// invalid options.
// `backend`: the eigen solver (empty: solve_lanczos; the MPI backend of
// linalg/slepc_eigen.hpp, collective, on every rank).
ModalAnalysis run_modal_analysis(const fe::Model& model, const linalg::EigenOptions& options,
                                 const fe::AssemblyOptions& assembly = {}, const linalg::EigenBackend& backend = {});

}  // namespace rigflex::reduction
