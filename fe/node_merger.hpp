#pragma once
// Finds or creates nodes by position, so that generated members and patches
// that meet at a point share one node. A hash grid keeps it O(1) per query.
#include <optional>
#include <unordered_map>

#include "fe/model.hpp"

namespace rigflex::fe {

class NodeMerger {
 public:
  // Indexes the model's existing nodes; `tol` is the merge distance [m].
  explicit NodeMerger(Model& model, double tol = 1e-6);
  // The id of a node within tol of x; a new node (next free id) if none.
  NodeId at(const Vec3& x);
  // The id of a node within tol of x, if there is one.
  std::optional<NodeId> find(const Vec3& x) const;

 private:
  using Key = std::array<long long, 3>;
  struct KeyHash {
    size_t operator()(const Key& k) const;
  };
  Key cell(const Vec3& x) const;
  void insert(NodeId id, const Vec3& x);

  Model& model_;
  double tol_;
  NodeId next_id_;
  std::unordered_multimap<Key, NodeId, KeyHash> grid_;
};

}  // namespace rigflex::fe
