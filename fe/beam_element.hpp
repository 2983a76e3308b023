#pragma once
// Two-node 3D beam: shear-deformable (Timoshenko, exact static interpolation)
// with Euler-Bernoulli as the shear-rigid limit; consistent mass with rotary
// inertia, or lumped mass.
#include <Eigen/Dense>

#include "fe/element_matrices.hpp"
#include "fe/model.hpp"

namespace rigflex::fe {

struct BeamProperties {
  double E = 0.0, G = 0.0, rho = 0.0;
  SectionProperties section;
  BeamTheory theory = BeamTheory::Timoshenko;
  MassKind mass = MassKind::Consistent;
  bool rotary_inertia = true;  // bending rotary inertia rho I
};

// Rows are the local axes (x along the member, y, z in the section plane).
// `orientation` approximates local z; see BeamElement::orientation.
Eigen::Matrix3d beam_local_axes(const Vec3& x1, const Vec3& x2, const std::optional<Vec3>& orientation);

// Local 12x12 matrices, DOFs [u v w rx ry rz] at node 1 then node 2.
ElementMatrices beam_local_matrices(double length, const BeamProperties& p);

// Global 12x12 matrices.
ElementMatrices beam_matrices(const Vec3& x1, const Vec3& x2, const std::optional<Vec3>& orientation,
                              const BeamProperties& p);

}  // namespace rigflex::fe
