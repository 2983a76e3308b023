// The rig model's own checks of the body: each names the key and what is
// wrong with it.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "support/rig_cases.hpp"

namespace {

using namespace rigflex;

std::string validation_error(const rig::RigModel& m) {
  try {
    m.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// A tensor scaled as D J D rounds d_i J_ij d_j and d_j J_ji d_i apart: a
// product of inertia off in its last bit was once reported as "must be
// finite".
TEST(RigModel, AnInertiaNotExactlySymmetricIsReportedAsSuch) {
  rig::RigModel m = test::noisy_quadrifilar();
  m.body.inertia(0, 1) = std::nextafter(m.body.inertia(1, 0), 1.0);
  const std::string e = validation_error(m);
  EXPECT_NE(e.find("body.inertia"), std::string::npos) << e;
  EXPECT_NE(e.find("symmetric"), std::string::npos) << e;
  EXPECT_EQ(e.find("finite"), std::string::npos) << e;
}

TEST(RigModel, ANonFiniteInertiaIsReportedAsSuch) {
  rig::RigModel m = test::noisy_quadrifilar();
  m.body.inertia(2, 2) = NAN;
  const std::string e = validation_error(m);
  EXPECT_NE(e.find("body.inertia: must be finite"), std::string::npos) << e;
  m.body.inertia(2, 2) = 40;
  EXPECT_EQ(validation_error(m), "");
}

}  // namespace
