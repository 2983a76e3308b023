#include "fe/assembly.hpp"

#include <algorithm>

#include "fe/distributing_coupling.hpp"
#include "fe/element_loop.hpp"
#include "fe/error.hpp"
#include "fe/skew.hpp"

namespace rigflex::fe {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;
using RowMajorMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Element triplets are flushed into the running sum in chunks so that a
// million-DOF shell model never holds all of its triplets at once.
class ChunkedAssembler {
 public:
  explicit ChunkedAssembler(Eigen::Index n) : K_(n, n), M_(n, n) {}

  void add(Eigen::Index i, Eigen::Index j, double k, double m) {
    if (k != 0.0) tk_.emplace_back(i, j, k);
    if (m != 0.0) tm_.emplace_back(i, j, m);
    if (tk_.size() + tm_.size() >= kChunk) flush();
  }

  void finish(SpMat& K, SpMat& M) {
    flush();
    K = std::move(K_);
    M = std::move(M_);
  }

 private:
  static constexpr size_t kChunk = size_t{1} << 23;

  static void flush_one(Triplets& t, SpMat& acc) {
    if (t.empty()) return;
    SpMat part(acc.rows(), acc.cols());
    part.setFromTriplets(t.begin(), t.end());
    if (acc.nonZeros() == 0)
      acc = std::move(part);
    else
      acc += part;
    t.clear();
  }
  void flush() {
    flush_one(tk_, K_);
    flush_one(tm_, M_);
  }

  SpMat K_, M_;
  Triplets tk_, tm_;
};

enum class DofState : unsigned char { Free, Fixed, Dependent };

std::vector<DofState> classify_dofs(const Model& model) {
  std::vector<DofState> state(6 * model.nodes.size(), DofState::Free);
  for (const RigidCoupling& c : model.couplings)
    for (NodeId d : c.dependents)
      for (int k = 0; k < 6; ++k)
        if (c.dofs[static_cast<size_t>(k)]) state[6 * model.node_index(d) + static_cast<size_t>(k)] = DofState::Dependent;
  for (const DistributingCoupling& c : model.distributing_couplings)
    for (int k = 0; k < 6; ++k) state[6 * model.node_index(c.reference) + static_cast<size_t>(k)] = DofState::Dependent;
  for (const Support& s : model.supports) {
    for (int k = 0; k < 6; ++k) {
      if (!s.fixed[static_cast<size_t>(k)]) continue;
      DofState& st = state[6 * model.node_index(s.node) + static_cast<size_t>(k)];
      if (st == DofState::Dependent)
        throw ModelError({"support", s.id, "dofs"},
                         "support '" + s.id + "' fixes " + std::string(dof_name(k)) + " of node " +
                             std::to_string(s.node) +
                             ", which a coupling drives; support a rigid coupling's reference, or a distributing "
                             "coupling's nodes");
      st = DofState::Fixed;
    }
  }
  return state;
}

// Rigid-body kinematics of a dependent node at offset r from its reference:
// u_d = u_r + theta_r x r, theta_d = theta_r.
Eigen::Matrix<double, 6, 6> rigid_link(const Vec3& r) {
  Eigen::Matrix<double, 6, 6> G = Eigen::Matrix<double, 6, 6>::Identity();
  G.topRightCorner<3, 3>() = -skew(r);
  return G;
}

// Builds T (full -> free) and the free-column bookkeeping.
DofMap build_dof_map(const Model& model) {
  const std::vector<DofState> state = classify_dofs(model);
  DofMap map;
  map.full_to_free.assign(state.size(), -1);
  for (size_t i = 0; i < state.size(); ++i) {
    if (state[i] != DofState::Free) continue;
    map.full_to_free[i] = static_cast<long>(map.node.size());
    map.node.push_back(model.nodes[i / 6].id);
    map.local.push_back(static_cast<int>(i % 6));
  }
  Triplets t;
  for (size_t i = 0; i < state.size(); ++i)
    if (state[i] == DofState::Free) t.emplace_back(static_cast<Eigen::Index>(i), map.full_to_free[i], 1.0);
  for (const RigidCoupling& c : model.couplings) {
    const size_t ref = 6 * model.node_index(c.reference);
    for (NodeId d : c.dependents) {
      const size_t dep = 6 * model.node_index(d);
      const Eigen::Matrix<double, 6, 6> G = rigid_link(model.position(d) - model.position(c.reference));
      for (int a = 0; a < 6; ++a) {
        if (!c.dofs[static_cast<size_t>(a)]) continue;
        for (int b = 0; b < 6; ++b) {
          const long col = map.full_to_free[ref + static_cast<size_t>(b)];
          if (G(a, b) != 0.0 && col >= 0) t.emplace_back(static_cast<Eigen::Index>(dep + a), col, G(a, b));
        }
      }
    }
  }
  // A distributing coupling's reference: rows of G over its nodes' free
  // translations (held ones contribute nothing; validate() refuses nodes
  // that another coupling drives).
  for (const DistributingCoupling& c : model.distributing_couplings) {
    std::vector<Vec3> x;
    for (NodeId n : c.nodes) x.push_back(model.position(n));
    const Eigen::MatrixXd G = *distributing_link(model.position(c.reference), x, c.weights);
    const size_t ref = 6 * model.node_index(c.reference);
    for (size_t i = 0; i < c.nodes.size(); ++i)
      for (int b = 0; b < 3; ++b) {
        const long col = map.full_to_free[6 * model.node_index(c.nodes[i]) + static_cast<size_t>(b)];
        if (col < 0) continue;
        for (int a = 0; a < 6; ++a) {
          const double g = G(a, 3 * static_cast<Eigen::Index>(i) + b);
          if (g != 0.0) t.emplace_back(static_cast<Eigen::Index>(ref + static_cast<size_t>(a)), col, g);
        }
      }
  }
  map.T.resize(static_cast<Eigen::Index>(state.size()), static_cast<Eigen::Index>(map.node.size()));
  map.T.setFromTriplets(t.begin(), t.end());
  return map;
}

// Removes free columns that carry neither stiffness nor mass.
void drop_unused(AssembledSystem& sys) {
  const Eigen::Index n = sys.K.cols();
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (const SpMat* A : {&sys.K, &sys.M})
    for (Eigen::Index j = 0; j < n; ++j)
      for (SpMat::InnerIterator it(*A, j); it; ++it)
        if (it.value() != 0.0) used[static_cast<size_t>(j)] = 1;
  std::vector<Eigen::Index> new_index(static_cast<size_t>(n), -1);
  Eigen::Index kept = 0;
  for (Eigen::Index j = 0; j < n; ++j)
    if (used[static_cast<size_t>(j)]) new_index[static_cast<size_t>(j)] = kept++;
  if (kept == n) return;

  Triplets sel;
  for (Eigen::Index j = 0; j < n; ++j)
    if (new_index[static_cast<size_t>(j)] >= 0) sel.emplace_back(j, new_index[static_cast<size_t>(j)], 1.0);
  SpMat P(n, kept);
  P.setFromTriplets(sel.begin(), sel.end());
  sys.K = SpMat(P.transpose() * sys.K * P);
  sys.M = SpMat(P.transpose() * sys.M * P);
  DofMap& d = sys.dofs;
  d.T = SpMat(d.T * P);
  std::vector<NodeId> node;
  std::vector<int> local;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (new_index[static_cast<size_t>(j)] < 0) continue;
    node.push_back(d.node[static_cast<size_t>(j)]);
    local.push_back(d.local[static_cast<size_t>(j)]);
  }
  d.node = std::move(node);
  d.local = std::move(local);
  for (long& f : d.full_to_free)
    if (f >= 0) f = new_index[static_cast<size_t>(f)];
}

}  // namespace

std::string DofMap::describe(Eigen::Index free_dof) const {
  const auto i = static_cast<size_t>(free_dof);
  return "node " + std::to_string(node.at(i)) + " " + std::string(dof_name(local.at(i)));
}

void assemble_full(const Model& model, SpMat& K, SpMat& M) {
  model.validate();
  ChunkedAssembler acc(6 * static_cast<Eigen::Index>(model.nodes.size()));
  for_each_element(model, [&](const std::vector<long>& dofs, const Eigen::MatrixXd& Ke, const Eigen::MatrixXd& Me) {
    for (size_t b = 0; b < dofs.size(); ++b)
      for (size_t a = 0; a < dofs.size(); ++a) {
        const auto ia = static_cast<Eigen::Index>(a), ib = static_cast<Eigen::Index>(b);
        acc.add(dofs[a], dofs[b], Ke(ia, ib), Me(ia, ib));
      }
  });
  acc.finish(K, M);
}

AssembledSystem assemble(const Model& model, const AssemblyOptions& options) {
  model.validate();
  AssembledSystem sys;
  sys.dofs = build_dof_map(model);
  const RowMajorMat Trow = sys.dofs.T;
  ChunkedAssembler acc(sys.dofs.free_count());
  // Each element DOF maps to a short list of (free column, weight): one entry
  // for a free DOF, none for a fixed one, up to four for a coupled one.
  std::vector<std::vector<std::pair<Eigen::Index, double>>> rows;
  const long total = element_count(model);
  long done = 0, reported = 0;  // elements; 2 % steps told
  for_each_element(model, [&](const std::vector<long>& dofs, const Eigen::MatrixXd& Ke, const Eigen::MatrixXd& Me) {
    if (options.progress && (++done * 50) / total > reported) {  // the last element is always step 50
      reported = (done * 50) / total;
      options.progress(done, total);
    }
    rows.assign(dofs.size(), {});
    for (size_t a = 0; a < dofs.size(); ++a)
      for (RowMajorMat::InnerIterator it(Trow, dofs[a]); it; ++it) rows[a].emplace_back(it.col(), it.value());
    for (size_t a = 0; a < dofs.size(); ++a)
      for (size_t b = 0; b < dofs.size(); ++b) {
        const auto ia = static_cast<Eigen::Index>(a), ib = static_cast<Eigen::Index>(b);
        const double k = Ke(ia, ib), m = Me(ia, ib);
        if (k == 0.0 && m == 0.0) continue;
        for (const auto& [i, wi] : rows[a])
          for (const auto& [j, wj] : rows[b]) acc.add(i, j, wi * wj * k, wi * wj * m);
      }
  });
  acc.finish(sys.K, sys.M);
  if (options.drop_unused_dofs) drop_unused(sys);
  return sys;
}

}  // namespace rigflex::fe
