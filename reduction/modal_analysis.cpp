#include "reduction/modal_analysis.hpp"

#include <unordered_set>

#include "fe/shell_centres.hpp"
#include "reduction/drilling_share.hpp"

namespace rigflex::reduction {

ModalAnalysis run_modal_analysis(const fe::Model& model, const linalg::EigenOptions& options,
                                 const fe::AssemblyOptions& assembly, const linalg::EigenBackend& backend) {
  ModalAnalysis a;
  a.system = fe::assemble(model, assembly);
  a.mass = fe::mass_properties(model);
  a.result = backend ? backend(a.system.K, a.system.M, options) : solve_lanczos(a.system.K, a.system.M, options);
  for (Eigen::Index dof : a.result.mechanism_dofs) a.mechanism.push_back(a.system.dofs.describe(dof));
  // An MPI backend may hold the vectors on rank 0 only: no summary elsewhere.
  if (a.result.converged_count > 0 && a.result.vectors.cols() == a.result.converged_count) {
    const Eigen::MatrixXd R = fe::rigid_body_modes_free(model, a.system.dofs, a.mass.cog);
    // Element coordinates (shells' centres, superelements' modes) are no translations.
    const std::vector<fe::NodeId> coordinates = fe::coordinate_nodes(model);
    const std::unordered_set<fe::NodeId> amplitude(coordinates.begin(), coordinates.end());
    std::vector<bool> translation(a.system.dofs.local.size());
    for (size_t i = 0; i < translation.size(); ++i)
      translation[i] = a.system.dofs.local[i] < 3 && !amplitude.count(a.system.dofs.node[i]);
    a.summary = summarize_modes(a.system.M, a.result.eigenvalues, a.result.vectors, R, translation);
    a.summary.drilling_share = shell_drilling_share(model, a.system.dofs, a.system.M, a.result.vectors);
  }
  return a;
}

}  // namespace rigflex::reduction
