#include "rig/integration.hpp"

#include <cmath>
#include <numbers>

namespace rigflex::rig {

ExternalLoad Push::at(double t) const {
  ExternalLoad e;
  if (t < 0 || t > duration_s) return e;
  const double shape = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * t / duration_s));
  e.force = shape * force;
  e.moment = shape * moment;
  return e;
}

const ExternalLoad* Push::load_at(double t, ExternalLoad& storage) const {
  if (t > duration_s) return nullptr;
  storage = at(t);
  return &storage;
}

}  // namespace rigflex::rig
