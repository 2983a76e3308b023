#include "fe/node_merger.hpp"

#include <cmath>

namespace rigflex::fe {

size_t NodeMerger::KeyHash::operator()(const Key& k) const {
  size_t h = 1469598103934665603ull;
  for (long long v : k) h = (h ^ static_cast<size_t>(v)) * 1099511628211ull;
  return h;
}

NodeMerger::NodeMerger(Model& model, double tol) : model_(model), tol_(tol), next_id_(model.next_node_id()) {
  for (const Node& n : model_.nodes) insert(n.id, n.x);
}

NodeMerger::Key NodeMerger::cell(const Vec3& x) const {
  return {static_cast<long long>(std::floor(x.x() / tol_)), static_cast<long long>(std::floor(x.y() / tol_)),
          static_cast<long long>(std::floor(x.z() / tol_))};
}

void NodeMerger::insert(NodeId id, const Vec3& x) { grid_.emplace(cell(x), id); }

std::optional<NodeId> NodeMerger::find(const Vec3& x) const {
  // A point within tol lies in the same or a neighbouring cell.
  const Key c = cell(x);
  for (long long dx = -1; dx <= 1; ++dx)
    for (long long dy = -1; dy <= 1; ++dy)
      for (long long dz = -1; dz <= 1; ++dz) {
        auto range = grid_.equal_range({c[0] + dx, c[1] + dy, c[2] + dz});
        for (auto it = range.first; it != range.second; ++it)
          if ((model_.position(it->second) - x).norm() <= tol_) return it->second;
      }
  return std::nullopt;
}

NodeId NodeMerger::at(const Vec3& x) {
  if (auto found = find(x)) return *found;
  const NodeId id = next_id_++;
  model_.add_node(id, x);
  insert(id, x);
  return id;
}

}  // namespace rigflex::fe
