#pragma once
// The cross-product matrix, fe's (fe/skew.hpp), where the rig's kinematics use it.
#include "fe/skew.hpp"

namespace rigflex::rig {

using fe::skew;

}  // namespace rigflex::rig
