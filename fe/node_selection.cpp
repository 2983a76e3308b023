#include "fe/node_selection.hpp"

#include <algorithm>

namespace rigflex::fe {
namespace {

template <class Pred>
std::vector<NodeId> select(const Model& m, Pred inside) {
  std::vector<NodeId> out;
  for (const Node& n : m.nodes)
    if (inside(n.x)) out.push_back(n.id);
  return out;
}

}  // namespace

std::vector<NodeId> nodes_in_box(const Model& m, const Vec3& lo, const Vec3& hi, double tolerance) {
  return select(m, [&](const Vec3& x) {
    return (x.array() >= lo.array() - tolerance).all() && (x.array() <= hi.array() + tolerance).all();
  });
}

std::vector<NodeId> nodes_on_segment(const Model& m, const Vec3& a, const Vec3& b, double tolerance) {
  const Vec3 d = b - a;
  const double length2 = d.squaredNorm();
  return select(m, [&](const Vec3& x) {
    const double s = std::clamp((x - a).dot(d) / length2, 0.0, 1.0);
    return (x - (a + s * d)).norm() <= tolerance;
  });
}

std::vector<NodeId> nodes_on_plane(const Model& m, const Vec3& p, const Vec3& n, double tolerance) {
  const Vec3 u = n.normalized();
  return select(m, [&](const Vec3& x) { return std::abs((x - p).dot(u)) <= tolerance; });
}

std::vector<NodeId> nodes_near(const Model& m, const Vec3& c, double radius) {
  return select(m, [&](const Vec3& x) { return (x - c).norm() <= radius; });
}

}  // namespace rigflex::fe
