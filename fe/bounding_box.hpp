#pragma once
// The sides of a model's axis-aligned bounding box: the length scale that
// turns a rotation into the motion it makes across the model (mode-shape
// display, zero-frequency mode selection).
#include "fe/model.hpp"

namespace rigflex::fe {

// hi - lo over the nodes' positions; zero for a model without nodes.
inline Vec3 bounding_box_sides(const Model& model) {
  if (model.nodes.empty()) return Vec3::Zero();
  Vec3 lo = model.nodes.front().x, hi = lo;
  for (const Node& n : model.nodes) {
    lo = lo.cwiseMin(n.x);
    hi = hi.cwiseMax(n.x);
  }
  return hi - lo;
}

}  // namespace rigflex::fe
