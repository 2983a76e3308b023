#pragma once
// What the two integrators of the rig share, the BDF one of simulation.hpp
// and generalized_alpha.hpp: the release push they apply and the statistics
// they count. Its own header so that neither integrator's header needs the
// other's.
#include <stdexcept>
#include <string>

#include "rig/rig_system.hpp"

namespace rigflex::rig {

// An integrator that cannot go on: which one, the time it reached and why.
// A numerical outcome of the model, not bad input; the command line names
// the rig and effect files it came from and the cures.
class IntegrationFailure : public std::runtime_error {
 public:
  IntegrationFailure(std::string method, double time_s, const std::string& why)
      : std::runtime_error(method + ": " + why + " at t = " + std::to_string(time_s) + " s"),
        method_(std::move(method)), time_s_(time_s), why_(why) {}
  const std::string& method() const { return method_; }  // "generalized-alpha" or "CVODE BDF"
  double time_s() const { return time_s_; }
  const std::string& why() const { return why_; }

 private:
  std::string method_;
  double time_s_;
  std::string why_;
};

struct IntegratorStatistics {
  long steps = 0, rhs_evaluations = 0, jacobian_evaluations = 0, error_test_failures = 0;
  long linear_setups = 0, newton_iterations = 0;
  long halvings = 0;  // generalized-alpha: steps taken again as two halves
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
