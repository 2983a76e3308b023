#pragma once
// The rig file of the CLI's compare and diagnose tests: 200 kg on three
// vertical 1 m rods at 0.5 m, CoG off centre, the spec's sensor noise (the
// trifilar of tests/support/rig_cases.hpp's noisy_trifilar, written out).
#include <string>

namespace rigflex::test {

inline std::string cli_trifilar_rig(const std::string& name) {
  return "name: " + name + R"(
geometry:
  gravity: 9.81
  reference_point: [0.0, 0.0, 0.0]
  rods:
    - {upper: [0.477668, 0.147760, 1.0], lower: [0.477668, 0.147760, 0.0], length: 1.0, encoder_axis: [0.955336489, 0.295520207, 0.0]}
    - {upper: [-0.366798, 0.339793, 1.0], lower: [-0.366798, 0.339793, 0.0], length: 1.0, encoder_axis: [-0.733596251, 0.679585565, 0.0]}
    - {upper: [-0.110870, -0.487553, 1.0], lower: [-0.110870, -0.487553, 0.0], length: 1.0, encoder_axis: [-0.221740238, -0.975105772, 0.0]}
body:
  mass: 200.0
  cog: [0.05, -0.03, -0.2]
  inertia: [18, 18, 36, 0, 0, 0]
sensors:
  sample_rate: 500
  load_cell: {noise: 1.0}
  encoder: {noise: 2.0e-5}
)";
}

}  // namespace rigflex::test
