#pragma once
// From the sensors to the motion and the loads of the carrying frame, sample
// by sample (shared/spec/rig-conventions.md): encoder angles -> rod
// directions u_i -> lower joint centres B_i = A_i + L_i u_i -> the pose of
// frame c by a least-squares point fit; load cells -> the loads the rods put
// on what hangs from them. The flexible algorithm moves A_i by the fixed
// frame's static compliance under the rod forces, stretches each rod by
// F_i / k_i, deforms the carrying frame's joints quasi-statically, and lets
// the forces act at the deformed points.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/identification_rig.hpp"
#include "rig/record.hpp"

namespace rigflex::identify {

// What the identifier works from, per sample. The pose is not fitted here:
// the joint centres are smoothed and differentiated first, and the rigid
// motion of frame c is fitted to them (positions, velocities,
// accelerations) only at the equation times (identification.cpp).
struct MotionSeries {
  Eigen::VectorXd t;
  // Rows are samples (each channel contiguous in time, as the filters read it).
  // Lower joint centres in G, 3 columns per rod, with the carrying frame's
  // own deformation taken out (R d_i subtracted), so that they move rigidly.
  Eigen::MatrixXd joints;
  // Resultant load of the rods on the identified system (G), and its moment
  // about the origin of G, the forces acting at the (deformed) joints. The
  // identified system is the record plus the rods' moving thirds (m_i / 3 at
  // B_i), whose weight is taken out of the loads here.
  Eigen::MatrixX3d force, moment;
};

// rig::RecordError when the record does not fit the rig (rod count, sizes) or a
// rod direction is impossible (the rod above its joint). The lower joints'
// consistency with a rigid carrying frame is checked where the pose is
// fitted (equation_samples).
MotionSeries motion_series(const IdentificationRig& rig, const rig::Record& record);

}  // namespace rigflex::identify
