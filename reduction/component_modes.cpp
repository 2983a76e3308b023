#include "reduction/component_modes.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "linalg/mechanism.hpp"
#include "linalg/stopwatch.hpp"

namespace rigflex::reduction {
namespace {

using linalg::seconds_since;

using Clock = std::chrono::steady_clock;

// A factorization whose smallest pivot is this small relative to its
// diagonal is singular to working precision (rounding leaves a mechanism's
// pivot at 1e-16..1e-14 of the diagonal; a stiff but sound frame stays many
// orders above).
constexpr double kSingularPivot = 1e-13;
// First guess of the mode count when modes are chosen by a cutoff frequency;
// doubled until the cutoff is passed.
constexpr int kCutoffFirstCount = 12;

// The four blocks of a symmetric matrix split into interior (sparse) and
// boundary (dense) parts. Only A_ib is kept of the off-diagonal pair (A_bi = A_ib').
struct Blocks {
  linalg::SpMat ii;
  Eigen::MatrixXd ib;  // interior x boundary
  Eigen::MatrixXd bb;
};

// position[j] >= 0: interior index; position[j] < 0: boundary index -position[j] - 1.
Blocks partition(const linalg::SpMat& A, const std::vector<Eigen::Index>& position, Eigen::Index ni, Eigen::Index nb) {
  Blocks b;
  b.ib = Eigen::MatrixXd::Zero(ni, nb);
  b.bb = Eigen::MatrixXd::Zero(nb, nb);
  b.ii.resize(ni, ni);
  b.ii.reserve(A.nonZeros());
  // Interior indices are increasing in the original order, so the rows of
  // every interior column arrive sorted and the block is built in place.
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    const Eigen::Index pj = position[static_cast<size_t>(j)];
    if (pj >= 0) b.ii.startVec(pj);
    for (linalg::SpMat::InnerIterator it(A, j); it; ++it) {
      const Eigen::Index pr = position[static_cast<size_t>(it.row())];
      if (pj >= 0 && pr >= 0) {
        b.ii.insertBack(pr, pj) = it.value();
      } else if (pj < 0 && pr >= 0) {
        b.ib(pr, -pj - 1) += it.value();
      } else if (pj < 0 && pr < 0) {
        b.bb(-pr - 1, -pj - 1) += it.value();
      }
    }
  }
  b.ii.finalize();
  return b;
}

Eigen::MatrixXd symmetric_part(const Eigen::MatrixXd& A) { return 0.5 * (A + A.transpose()); }

void validate_boundary(const linalg::SpMat& K, const linalg::SpMat& M, const std::vector<Eigen::Index>& boundary) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    throw std::invalid_argument("reduce_component: K and M must be square and of equal size");
  }
  if (boundary.empty()) throw std::invalid_argument("reduce_component: the boundary (interface) is empty");
  std::vector<bool> seen(static_cast<size_t>(K.rows()), false);
  for (Eigen::Index b : boundary) {
    if (b < 0 || b >= K.rows()) {
      throw std::invalid_argument("reduce_component: boundary DOF " + std::to_string(b) + " is outside 0.." +
                                  std::to_string(K.rows() - 1));
    }
    if (seen[static_cast<size_t>(b)]) {
      throw std::invalid_argument("reduce_component: boundary DOF " + std::to_string(b) + " is listed twice");
    }
    seen[static_cast<size_t>(b)] = true;
  }
}

// Lowest fixed-interface modes on the factorization of K_ii (shift 0).
linalg::EigenResult fixed_interface_modes(const linalg::SpMat& Kii, const linalg::SpMat& Mii, linalg::SparseCholesky& factor,
                                  const ComponentModeOptions& o) {
  linalg::EigenOptions eo;
  eo.shift = 0.0;
  eo.tolerance = o.tolerance;
  eo.progress = o.progress;
  const int n = static_cast<int>(std::min<Eigen::Index>(Kii.rows(), 1 << 30));
  const auto solve = [&] {
    return o.eigen_backend ? o.eigen_backend(Kii, Mii, eo) : solve_lanczos(Kii, Mii, eo, factor);
  };
  if (!o.cutoff_hz) {
    eo.count = o.modes;
    return solve();
  }
  const double cutoff = std::pow(2 * M_PI * *o.cutoff_hz, 2);
  eo.count = std::min(kCutoffFirstCount, n);
  for (;;) {
    linalg::EigenResult r = solve();
    const bool passed = r.converged_count > 0 && r.eigenvalues(r.converged_count - 1) > cutoff;
    if (!r.converged || passed || eo.count == n) {
      if (!r.converged) return r;
      Eigen::Index keep = 0;
      while (keep < r.eigenvalues.size() && r.eigenvalues(keep) <= cutoff) ++keep;
      r.eigenvalues.conservativeResize(keep);
      r.vectors.conservativeResize(Eigen::NoChange, keep);
      r.residuals.conservativeResize(keep);
      r.backward_errors.conservativeResize(keep);
      r.converged_count = static_cast<int>(keep);
      r.requested = static_cast<int>(keep);
      return r;
    }
    eo.count = std::min(2 * eo.count, n);
  }
}

// Where each free DOF goes: boundary DOF k at -k - 1, interior DOFs numbered
// in order; `interior` maps back.
struct DofPartition {
  std::vector<Eigen::Index> position;
  std::vector<Eigen::Index> interior;  // interior index -> free DOF
};

DofPartition partition_dofs(Eigen::Index n, const std::vector<Eigen::Index>& boundary) {
  const auto nb = static_cast<Eigen::Index>(boundary.size());
  DofPartition p;
  p.position.assign(static_cast<size_t>(n), 0);
  for (Eigen::Index k = 0; k < nb; ++k) p.position[static_cast<size_t>(boundary[static_cast<size_t>(k)])] = -k - 1;
  p.interior.reserve(static_cast<size_t>(n - nb));
  for (Eigen::Index j = 0; j < n; ++j) {
    if (p.position[static_cast<size_t>(j)] >= 0) {
      p.position[static_cast<size_t>(j)] = static_cast<Eigen::Index>(p.interior.size());
      p.interior.push_back(j);
    }
  }
  return p;
}

// Everything is boundary: the reduction is a reordering.
ReducedMatrices boundary_only(const linalg::SpMat& K, const linalg::SpMat& M, const std::vector<Eigen::Index>& boundary,
                              bool keep_basis) {
  const auto nb = static_cast<Eigen::Index>(boundary.size());
  ReducedMatrices out;
  Eigen::MatrixXd Kd(K), Md(M);
  out.K.resize(nb, nb);
  out.M.resize(nb, nb);
  for (Eigen::Index r = 0; r < nb; ++r)
    for (Eigen::Index c = 0; c < nb; ++c) {
      out.K(r, c) = Kd(boundary[size_t(r)], boundary[size_t(c)]);
      out.M(r, c) = Md(boundary[size_t(r)], boundary[size_t(c)]);
    }
  if (keep_basis) {
    out.basis = Eigen::MatrixXd::Zero(K.rows(), nb);
    for (Eigen::Index k = 0; k < nb; ++k) out.basis(boundary[size_t(k)], k) = 1.0;
  }
  out.ok = true;
  return out;
}

// The reduced matrices on the basis T = [I 0; Psi Phi] (boundary, then the
// fixed-interface modes, whose eigenvalues are in out.mode_eigenvalues).
void project(const Blocks& Kb, const Blocks& Mb, const Eigen::MatrixXd& Psi, const Eigen::MatrixXd& Phi,
             ReducedMatrices& out) {
  const Eigen::Index nb = Psi.cols(), nm = Phi.cols();
  // K_r = [K_bb + K_bi Psi, 0; 0, Omega^2].
  out.K = Eigen::MatrixXd::Zero(nb + nm, nb + nm);
  out.K.topLeftCorner(nb, nb) = symmetric_part(Kb.bb + Kb.ib.transpose() * Psi);
  for (Eigen::Index k = 0; k < nm; ++k) out.K(nb + k, nb + k) = out.mode_eigenvalues(k);
  // M_r = T' M T, blockwise with the sparse M_ii.
  const Eigen::MatrixXd MiiPsi = Mb.ii * Psi;
  const Eigen::MatrixXd MibPsi = Mb.ib.transpose() * Psi;  // M_bi Psi
  out.M.resize(nb + nm, nb + nm);
  out.M.topLeftCorner(nb, nb) = symmetric_part(Mb.bb + MibPsi + MibPsi.transpose() + Psi.transpose() * MiiPsi);
  if (nm > 0) {
    const Eigen::MatrixXd MiiPhi = Mb.ii * Phi;
    const Eigen::MatrixXd Mbq = Mb.ib.transpose() * Phi + MiiPsi.transpose() * Phi;
    out.M.topRightCorner(nb, nm) = Mbq;
    out.M.bottomLeftCorner(nm, nb) = Mbq.transpose();
    out.M.bottomRightCorner(nm, nm) = symmetric_part(Phi.transpose() * MiiPhi);
  }
}

// T in the free DOFs' order.
Eigen::MatrixXd basis_of(Eigen::Index n, const std::vector<Eigen::Index>& boundary,
                         const std::vector<Eigen::Index>& interior, const Eigen::MatrixXd& Psi,
                         const Eigen::MatrixXd& Phi) {
  const auto nb = static_cast<Eigen::Index>(boundary.size());
  const Eigen::Index nm = Phi.cols();
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(n, nb + nm);
  for (Eigen::Index k = 0; k < nb; ++k) basis(boundary[static_cast<size_t>(k)], k) = 1.0;
  for (Eigen::Index r = 0; r < static_cast<Eigen::Index>(interior.size()); ++r) {
    const Eigen::Index row = interior[static_cast<size_t>(r)];
    basis.row(row).head(nb) = Psi.row(r);
    if (nm > 0) basis.row(row).tail(nm) = Phi.row(r);
  }
  return basis;
}

}  // namespace

void ComponentModeOptions::validate(Eigen::Index interior_dofs) const {
  if (method == ReductionMethod::guyan) {
    if (modes != 0 || cutoff_hz) {
      throw std::invalid_argument("modes / cutoff: Guyan reduction keeps no fixed-interface modes");
    }
  } else {
    if (modes < 0) throw std::invalid_argument("modes: must be >= 0, got " + std::to_string(modes));
    if (modes > 0 && cutoff_hz) throw std::invalid_argument("modes / cutoff: give a mode count or a cutoff, not both");
    if (modes == 0 && !cutoff_hz) {
      throw std::invalid_argument("modes / cutoff: Craig-Bampton needs a mode count or a cutoff frequency");
    }
    if (cutoff_hz && !(*cutoff_hz > 0)) {
      throw std::invalid_argument("cutoff: must be a positive frequency in Hz, got " + std::to_string(*cutoff_hz));
    }
    if (modes > interior_dofs) {
      throw std::invalid_argument("modes: " + std::to_string(modes) + " fixed-interface modes asked for, but the " +
                                  "interior has only " + std::to_string(interior_dofs) + " DOFs");
    }
  }
  if (!(tolerance > 0 && tolerance < 1)) throw std::invalid_argument("tolerance: must lie in (0, 1)");
}

ReducedMatrices reduce_component(const linalg::SpMat& K, const linalg::SpMat& M, const std::vector<Eigen::Index>& boundary,
                                 const ComponentModeOptions& options) {
  validate_boundary(K, M, boundary);
  const Eigen::Index n = K.rows();
  const auto nb = static_cast<Eigen::Index>(boundary.size());
  const Eigen::Index ni = n - nb;
  options.validate(ni);

  ReducedMatrices out;
  auto& stats = out.statistics;
  auto t0 = Clock::now();
  const DofPartition dofs = partition_dofs(n, boundary);
  if (ni == 0) return boundary_only(K, M, boundary, options.keep_basis);
  Blocks Kb = partition(K, dofs.position, ni, nb);
  Blocks Mb = partition(M, dofs.position, ni, nb);
  stats.partition_seconds = seconds_since(t0);

  t0 = Clock::now();
  linalg::SparseCholesky factor;
  factor.set_memory_limit(options.max_factor_bytes);
  if (options.analyzed) factor.on_analysis(options.analyzed);
  const linalg::FactorStatus status = factor.factorize(Kb.ii);
  stats.factor_seconds = seconds_since(t0);
  stats.factor_bytes = factor.statistics().factor_bytes;
  if (status.over_memory_limit) {
    out.over_memory_limit = true;
    out.message = "the interior stiffness K_ii: " + status.message;
    return out;
  }
  if (!status.ok || status.min_relative_pivot < kSingularPivot) {
    for (Eigen::Index d : linalg::mechanism_dofs(Kb.ii)) out.mechanism_dofs.push_back(dofs.interior[static_cast<size_t>(d)]);
    out.message = "the interior stiffness K_ii is singular with the interface DOFs held: the interface does not "
                  "hold the frame statically (" + std::to_string(out.mechanism_dofs.size()) + " DOFs move freely)";
    return out;
  }

  t0 = Clock::now();
  Eigen::MatrixXd Psi = factor.solve(Kb.ib);
  Psi = -Psi;
  stats.solves += nb;
  stats.constraint_seconds = seconds_since(t0);

  Eigen::MatrixXd Phi;
  if (options.method == ReductionMethod::craig_bampton) {
    t0 = Clock::now();
    out.modes_result = fixed_interface_modes(Kb.ii, Mb.ii, factor, options);
    stats.eigen_seconds = seconds_since(t0);
    stats.solves += out.modes_result.operator_applications;
    if (!out.modes_result.converged) {
      out.message = "fixed-interface modes did not converge: " + out.modes_result.message;
      return out;
    }
    out.mode_eigenvalues = out.modes_result.eigenvalues;
    Phi = std::move(out.modes_result.vectors);  // moved into the basis below; the result keeps its checks
    out.modes_result.vectors.resize(0, 0);
  }
  t0 = Clock::now();
  project(Kb, Mb, Psi, Phi, out);
  stats.projection_seconds = seconds_since(t0);
  if (options.keep_basis) out.basis = basis_of(n, boundary, dofs.interior, Psi, Phi);
  out.ok = true;
  return out;
}

}  // namespace rigflex::reduction
