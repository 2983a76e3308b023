#include "fe/assembly_size.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "fe/shell_point_mass.hpp"

namespace rigflex::fe {
namespace {

// Node adjacency as sorted lists of node indices: one list per node.
class Adjacency {
 public:
  explicit Adjacency(size_t nodes) : near_(nodes), used_(nodes, false) {}

  template <class Ids>
  void couple(const Model& model, const Ids& ids) {
    idx_.clear();
    for (NodeId id : ids) idx_.push_back(model.node_index(id));
    for (size_t a : idx_) {
      used_[a] = true;
      for (size_t b : idx_) near_[a].push_back(b);
    }
    triplets_ += 36.0 * static_cast<double>(idx_.size() * idx_.size());
  }

  // A rigid coupling: its reference takes on the dependents' rows, a star
  // (the dependents are eliminated, never coupled with each other).
  void star(const Model& model, NodeId centre, const std::vector<NodeId>& leaves) {
    const size_t c = model.node_index(centre);
    used_[c] = true;
    near_[c].push_back(c);
    for (NodeId id : leaves) {
      const size_t l = model.node_index(id);
      used_[l] = true;
      near_[c].push_back(l);
      near_[l].push_back(c);
    }
  }

  AssemblySize size() {
    AssemblySize s;
    double pairs = 0;
    for (size_t a = 0; a < near_.size(); ++a) {
      if (!used_[a]) continue;
      std::vector<size_t>& n = near_[a];
      std::sort(n.begin(), n.end());
      pairs += static_cast<double>(std::unique(n.begin(), n.end()) - n.begin());
      s.dofs += 6;
    }
    s.nonzeros = 36.0 * pairs;
    // Compressed columns: 12 bytes per entry, 4 per column. The assembly
    // holds the full K and M while it makes their constrained copies, and
    // one chunk of element triplets (16 bytes each, at most 2^23 at a time:
    // fe/assembly.cpp) while it sums them in. Weighted by what the 100k-DOF
    // bench plate's peak showed (193 MB above the base for 127 MB of K and
    // M and a 134 MB chunk; this gives 257 MB): a bound within 1.5 x, not
    // a measurement.
    const double pair = 2.0 * (12.0 * s.nonzeros + 4.0 * static_cast<double>(s.dofs));
    s.bytes = 1.5 * pair + 0.5 * 16.0 * std::min(2.0 * triplets_, 8388608.0);
    return s;
  }

 private:
  std::vector<std::vector<size_t>> near_;
  std::vector<bool> used_;
  std::vector<size_t> idx_;
  double triplets_ = 0;
};

}  // namespace

AssemblySize assembly_size(const Model& model) {
  Adjacency adj(model.nodes.size());
  for (const BeamElement& b : model.beams) adj.couple(model, b.nodes);
  for (const ShellElement& s : model.shells) {
    if (s.centre == 0) {
      adj.couple(model, s.nodes);
      continue;
    }
    std::vector<NodeId> nodes = s.nodes;
    nodes.push_back(s.centre);
    adj.couple(model, nodes);
  }
  // Counted as six DOFs per node like the rest: solids' unused rotations are
  // dropped later, so the estimate errs on the safe side.
  for (const SolidElement& s : model.solids) adj.couple(model, s.nodes);
  // A rotary mass on a shell node acts over its footprint (shell_point_mass.hpp).
  for (const PointMassMatrix& p : point_mass_matrices(model)) {
    std::vector<NodeId> nodes;
    for (long d : p.dofs) {
      const NodeId id = model.nodes[static_cast<size_t>(d / 6)].id;
      if (nodes.empty() || nodes.back() != id) nodes.push_back(id);
    }
    adj.couple(model, nodes);
  }
  for (const Spring& s : model.springs) {
    adj.couple(model, s.other ? std::vector<NodeId>{s.node, *s.other} : std::vector<NodeId>{s.node});
  }
  for (const Superelement& e : model.superelements) {
    std::vector<NodeId> nodes = e.modal_nodes;
    for (const SuperelementDof& d : e.interface) nodes.push_back(d.node);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    adj.couple(model, nodes);
  }
  for (const RigidCoupling& c : model.couplings) adj.star(model, c.reference, c.dependents);
  // Whatever is attached at the reference couples all of the coupling's
  // nodes with each other once the reference is eliminated.
  for (const DistributingCoupling& c : model.distributing_couplings) {
    std::vector<NodeId> all = c.nodes;
    all.push_back(c.reference);
    adj.couple(model, all);
  }
  return adj.size();
}

namespace {

std::string format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

}  // namespace

std::string bytes_text(double bytes) {
  if (bytes >= 1073741824.0) return format("%.2f GiB", bytes / 1073741824.0);
  return format("%.1f MiB", bytes / 1048576.0);
}

std::string assembly_refusal(const AssemblySize& size, double limit_bytes) {
  if (limit_bytes <= 0 || size.bytes <= limit_bytes) return "";
  return "the model's " + std::to_string(size.dofs) + " DOFs and " + format("%.3g", size.nonzeros) +
         " nonzeros need about " + bytes_text(size.bytes) + " to assemble, above the limit of " +
         bytes_text(limit_bytes);
}

}  // namespace rigflex::fe
