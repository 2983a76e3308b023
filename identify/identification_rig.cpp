#include "identify/identification_rig.hpp"

#include <Eigen/Cholesky>
#include <stdexcept>
#include <string>

namespace rigflex::identify {

const char* to_string(IdentificationAlgorithm a) {
  return a == IdentificationAlgorithm::rigid ? "rigid" : "flexible";
}

void IdentificationRig::validate() const {
  const int n = rods();
  if (n < 3 || n > 4) throw std::invalid_argument("identification: the rig needs 3 or 4 rods, has " + std::to_string(n));
  if (!(mass > 0) || !std::isfinite(mass)) throw std::invalid_argument("identification: mass must be positive");
  if (rod_mass.size() != n || (rod_mass.array() < 0).any()) {
    throw std::invalid_argument("identification: rod_mass needs one value >= 0 per rod");
  }
  if (rod_stiffness.size() && (rod_stiffness.size() != n || !(rod_stiffness.array() > 0).all())) {
    throw std::invalid_argument("identification: rod_stiffness needs one positive value per rod");
  }
  if (fixed_compliance.size() && (fixed_compliance.rows() != 3 * n || fixed_compliance.cols() != 3 * n)) {
    throw std::invalid_argument("identification: fixed_compliance must be 3n x 3n");
  }
  if (carrying_frame && carrying_frame->psi.rows() != 3 * n) {
    throw std::invalid_argument("identification: carrying frame joints do not match the rod count");
  }
}

namespace {

// Static condensation onto the joint translations: the frame carries no load
// but the rod forces at its joints, so A's displacement is E' K^-1 E f.
Eigen::MatrixXd joint_compliance(const rig::FixedFrameModel& f, int rods) {
  const Eigen::Index nq = f.K.rows();
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(nq, 3 * rods);
  for (int i = 0; i < rods; ++i) {
    for (int d = 0; d < 3; ++d) E(f.joint_row[i] + d, 3 * i + d) = 1.0;
  }
  Eigen::LDLT<Eigen::MatrixXd> ldlt(f.K);
  if (ldlt.info() != Eigen::Success) throw std::invalid_argument("fixed frame: reduced stiffness cannot be factored");
  Eigen::MatrixXd G = E.transpose() * ldlt.solve(E);
  return 0.5 * (G + G.transpose());
}

}  // namespace

IdentificationRig identification_rig(const rig::RigModel& model, IdentificationAlgorithm algorithm,
                                     const StiffnessScale& scale) {
  model.validate();
  rig::RigAssembly a;
  a.geometry = model.geometry;
  a.body = model.body;
  a.rod_mass.assign(model.geometry.rods.size(), 0.0);
  a.rod_stiffness = model.rods.stiffness;
  for (const auto& e : model.effects) e->build(a);

  IdentificationRig rig;
  rig.algorithm = algorithm;
  rig.geometry = a.geometry;
  rig.mass = model.body.mass;
  rig.rod_mass = Eigen::Map<const Eigen::VectorXd>(a.rod_mass.data(), static_cast<Eigen::Index>(a.rod_mass.size()));
  rig.measurement_chain = model.effects;
  if (algorithm == IdentificationAlgorithm::flexible) {
    if (!a.rod_stiffness.empty()) {
      rig.rod_stiffness = scale.rods * Eigen::Map<const Eigen::VectorXd>(
                                           a.rod_stiffness.data(), static_cast<Eigen::Index>(a.rod_stiffness.size()));
    }
    if (a.fixed_frame) rig.fixed_compliance = joint_compliance(*a.fixed_frame, rig.rods()) / scale.fixed_frame;
    rig.carrying_frame = a.carrying_frame;
    if (rig.carrying_frame) rig.carrying_frame->omega2 *= scale.carrying_frame;
  }
  rig.validate();
  return rig;
}

}  // namespace rigflex::identify
