#include "diagnose/effect_chain.hpp"

#include <algorithm>
#include <stdexcept>

namespace rigflex::diagnose {

EffectGroup::EffectGroup(std::vector<std::shared_ptr<const rig::Effect>> members) : members_(std::move(members)) {
  if (members_.empty()) throw std::invalid_argument("an effect group needs at least one effect");
  for (const auto& m : members_) name_ += (name_.empty() ? "" : "+") + std::string(m->name());
}

void EffectGroup::validate(int rods) const {
  for (const auto& m : members_) m->validate(rods);
}

void EffectGroup::build(rig::RigAssembly& a) const {
  for (const auto& m : members_) m->build(a);
}

void EffectGroup::add_loads(const rig::Kinematics& k, rig::Loads& l) const {
  for (const auto& m : members_) m->add_loads(k, l);
}

void EffectGroup::measure(rig::SensorSample& s) const {
  for (const auto& m : members_) m->measure(s);
}

void EffectGroup::unmeasure(rig::SensorSample& s) const {
  // The inverse of a chain of measurements: the last one undone first.
  for (auto m = members_.rbegin(); m != members_.rend(); ++m) (*m)->unmeasure(s);
}

bool EffectGroup::dissipative() const {
  return std::any_of(members_.begin(), members_.end(), [](const auto& m) { return m->dissipative(); });
}

EffectCandidate chained_candidate(const std::vector<const EffectCandidate*>& accepted, const EffectCandidate* next) {
  std::vector<const EffectCandidate*> members = accepted;
  if (next) members.push_back(next);
  if (members.empty()) throw std::invalid_argument("chained_candidate: no effect");
  EffectCandidate c;
  c.effect = members.back()->effect;
  c.advice = members.back()->advice;
  c.evidence = members.back()->evidence;
  c.stand_in = members.back()->stand_in;
  for (size_t m = 0; m < members.size(); ++m) {
    for (auto p : members[m]->parameters) {
      if (m < accepted.size()) p.name = members[m]->effect + "." + p.name;
      c.parameters.push_back(std::move(p));
    }
  }
  // Each member with where its parameters start in theta and how many.
  auto segments = [members](auto&& each) {
    Eigen::Index at = 0;
    for (const EffectCandidate* m : members) {
      const auto n = static_cast<Eigen::Index>(m->parameters.size());
      each(*m, at, n);
      at += n;
    }
  };
  c.make = [segments](const Eigen::VectorXd& theta) -> std::shared_ptr<const rig::Effect> {
    std::vector<std::shared_ptr<const rig::Effect>> made;
    segments([&](const EffectCandidate& m, Eigen::Index at, Eigen::Index n) {
      if (auto e = m.make(theta.segment(at, n))) made.push_back(std::move(e));
    });
    if (made.empty()) return nullptr;
    if (made.size() == 1) return made.front();
    return std::make_shared<EffectGroup>(std::move(made));
  };
  c.rig_block = [segments](const Eigen::VectorXd& theta, const Eigen::VectorXd& std) {
    std::string block;
    segments([&](const EffectCandidate& m, Eigen::Index at, Eigen::Index n) {
      const Eigen::VectorXd x = theta.segment(at, n);
      if (m.make(x)) block += m.rig_block(x, std.size() > 0 ? Eigen::VectorXd(std.segment(at, n)) : std);
    });
    return block;
  };
  return c;
}

}  // namespace rigflex::diagnose
