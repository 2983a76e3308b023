#pragma once
// Nodes chosen by where they are, for node sets, supports and couplings:
// in a box, on a segment, on a plane, within a distance of a point. Each
// returns the matching nodes in the model's node order (empty if none).
#include <vector>

#include "fe/model.hpp"

namespace rigflex::fe {

// Inside the axis-aligned box [lo, hi], widened by `tolerance`.
std::vector<NodeId> nodes_in_box(const Model& m, const Vec3& lo, const Vec3& hi, double tolerance);
// Within `tolerance` of the segment from a to b (a != b).
std::vector<NodeId> nodes_on_segment(const Model& m, const Vec3& a, const Vec3& b, double tolerance);
// Within `tolerance` of the plane through p with normal n (n != 0).
std::vector<NodeId> nodes_on_plane(const Model& m, const Vec3& p, const Vec3& n, double tolerance);
// Within `radius` of the point c.
std::vector<NodeId> nodes_near(const Model& m, const Vec3& c, double radius);

}  // namespace rigflex::fe
