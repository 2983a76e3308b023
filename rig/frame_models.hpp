#pragma once
// Reduced frames (from `rigflex reduce` or reduce_frame in-process) turned
// into the rig's frame models: each rod's joint matched to an interface node.
#include "reduction/reduced_model.hpp"
#include "rig/effect.hpp"

namespace rigflex::rig {

struct FrameMatching {
  Vec3 offset = Vec3::Zero();   // added to the model's node coordinates (G for the fixed frame, c for the carrying frame)
  double tolerance = 0.01;      // m: a joint centre and its interface node must agree this well
};

// A grounded frame whose interface nodes are the upper joint centres A_i.
// std::invalid_argument when a joint has no node within the tolerance, the
// frame is not grounded, or translations of a node are not retained.
FixedFrameModel fixed_frame_model(const reduction::ReducedFrame& frame, const RigGeometry& geometry,
                                  const FrameMatching& matching = {});

// A free-free frame whose interface nodes are the lower joint centres B_i:
// its elastic modes about the mean axes (exactly six rigid-body modes
// required).
CarryingFrameModel carrying_frame_model(const reduction::ReducedFrame& frame, const RigGeometry& geometry,
                                        const FrameMatching& matching = {});

}  // namespace rigflex::rig
