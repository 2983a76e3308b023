#pragma once
// What the two integrators of the rig share, the BDF one of simulation.hpp
// and generalized_alpha.hpp: the release push they apply and the statistics
// they count. Its own header so that neither integrator's header needs the
// other's.
#include "rig/rig_system.hpp"

namespace rigflex::rig {

struct IntegratorStatistics {
  long steps = 0, rhs_evaluations = 0, jacobian_evaluations = 0, error_test_failures = 0;
  long linear_setups = 0, newton_iterations = 0;
};

// The raised-cosine push of the release protocol.
struct Push {
  double duration_s = 1.0;
  Vec3 force = Vec3::Zero();   // peak, G, at the CoG
  Vec3 moment = Vec3::Zero();  // peak, G
  ExternalLoad at(double t) const;
  // at(t) into `storage`, or nullptr after the push (nothing to add).
  const ExternalLoad* load_at(double t, ExternalLoad& storage) const;
};

}  // namespace rigflex::rig
