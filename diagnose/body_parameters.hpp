#pragma once
// The body's mass properties as parameters of diagnose's fits. A user never
// knows the body exactly (that is why it is measured): the CoG comes from a
// static reference measurement, the inertia from a rigid identification.
// Held fixed, their errors show as residuals that the catalogue's effects
// then absorb (a CoG 5 mm too high swings like rods 5 mm too short), and the
// ranking follows the parameters the user is least sure of, not the missing
// physics. So every fit - the baseline and each candidate - refits them,
// each offset from the rig file's value with the user's stated standard
// deviation (rig::BodyUncertainty) as a Gaussian prior: a maximum a
// posteriori fit in which the data decide wherever they can. Where the rig
// file states how well it knows the rods' stiffness (rods.uncertainty), a
// common factor on it is refitted the same way: a parameter already in the
// model, suspected like the body; so are the parameters of effects already
// in the model whose uncertainty the rig file states (rig/effect_uncertainty.hpp).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rig/effect_kinds.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::diagnose {

struct BodyParameters {
  // Of the ten (cog x y z, then Jxx Jyy Jzz Jxy Jxz Jyz, then the rods'
  // stiffness, an offset in % of the rig file's), those with a standard
  // deviation above zero, in that order; then kEffectItems + i for each
  // item of the effects' stated uncertainties (RigModel::effect_uncertainty,
  // their items in order, counted across effects).
  std::vector<int> components;
  static constexpr int kEffectItems = 10;
  std::vector<rig::FitParameter> parameters;  // name, unit, probe, plausible range (+-3 sigma)
  Eigen::VectorXd sigma;                      // prior standard deviations
  int size() const { return static_cast<int>(components.size()); }
};

BodyParameters body_parameters(const rig::RigModel& model);

// The body with the offsets `delta` (one per fitted component) added.
fe::MassProperties body_with(const fe::MassProperties& body, const BodyParameters& p, const Eigen::VectorXd& delta);
// The model with the offsets `delta` applied: the body's, the rods' stiffness
// and the refitted effects' (each rebuilt by its kind from the offset parameters).
rig::RigModel model_with(const rig::RigModel& model, const BodyParameters& p, const Eigen::VectorXd& delta);

}  // namespace rigflex::diagnose
