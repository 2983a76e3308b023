#pragma once
// Effects accepted one after another (diagnose's chain, diagnosis.hpp): the
// next candidate is fitted on top of the effects already accepted, whose
// parameters are refitted with it - two effects present bias each other's
// fit, so neither keeps the values it had alone.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "diagnose/effect_candidates.hpp"
#include "rig/effect.hpp"

namespace rigflex::diagnose {

// Several effects acting as one: every hook forwards to each member, in order.
class EffectGroup : public rig::Effect {
 public:
  explicit EffectGroup(std::vector<std::shared_ptr<const rig::Effect>> members);
  const char* name() const override { return name_.c_str(); }  // the members' names joined by '+'
  void validate(int rods) const override;
  void build(rig::RigAssembly& a) const override;
  void add_loads(const rig::Kinematics& k, rig::Loads& l) const override;
  void measure(rig::SensorSample& s) const override;
  void unmeasure(rig::SensorSample& s) const override;
  bool dissipative() const override;

 private:
  std::vector<std::shared_ptr<const rig::Effect>> members_;
  std::string name_;
};

// A candidate whose parameters are every accepted effect's (in order, named
// "<effect>.<parameter>") and then `next`'s (nullptr: the accepted ones
// alone). It is named after `next` (the last accepted one without it); its
// make() builds all of them (nullptr when none amounts to an effect), its
// rig_block() writes a block per effect. The candidates must outlive it.
EffectCandidate chained_candidate(const std::vector<const EffectCandidate*>& accepted, const EffectCandidate* next);

}  // namespace rigflex::diagnose
