#pragma once
// What the identifier knows about the rig: the calibrated geometry, the
// static weighing, the rods' mass and, for the flexible algorithm, the
// compliance of rods and frames from the reduced models (the files
// `rigflex reduce` exports, read through the rig file). The rigid algorithm
// assumes rigid frames and rods: nominal A_i, L_i, B_i.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "rig/effect.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::identify {

enum class IdentificationAlgorithm { rigid, flexible };
const char* to_string(IdentificationAlgorithm a);

struct IdentificationRig {
  IdentificationAlgorithm algorithm = IdentificationAlgorithm::rigid;
  rig::RigGeometry geometry;       // the model's geometry errors applied (calibration)
  double mass = 0.0;          // kg: what hangs from the rods, from static weighing
  Eigen::VectorXd rod_mass;   // kg per rod (uniform rods: see rig_system.hpp)
  // Flexible only. Empty: rigid rods / rigid fixed frame / rigid carrying frame.
  Eigen::VectorXd rod_stiffness;    // N/m per rod
  Eigen::MatrixXd fixed_compliance; // 3n x 3n: displacement of A_i (G) per unit force at A_j (G)
  std::optional<rig::CarryingFrameModel> carrying_frame;
  // Effects whose measurement chain the identifier undoes (encoder offsets, load-cell gains).
  std::vector<std::shared_ptr<const rig::Effect>> measurement_chain;

  int rods() const { return geometry.rod_count(); }
  bool flexible() const { return rod_stiffness.size() || fixed_compliance.size() || carrying_frame.has_value(); }
  void validate() const;  // std::invalid_argument naming the field
};

// From the rig model: geometry with the model's geometry errors, the body's
// mass as the static weighing, rod masses, the measurement chain; for the
// flexible algorithm also rod stiffness and the frames' compliance (the
// static condensation of the reduced fixed frame onto its joints).
// `scale` multiplies the stiffness of the fixed frame, the rods and the
// carrying frame as RigSystem's scaled constructor does (design sweeps).
struct StiffnessScale {
  double fixed_frame = 1.0, rods = 1.0, carrying_frame = 1.0;
};
IdentificationRig identification_rig(const rig::RigModel& model, IdentificationAlgorithm algorithm,
                                     const StiffnessScale& scale = {});

}  // namespace rigflex::identify
