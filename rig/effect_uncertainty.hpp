#pragma once
// How well the rig file knows an effect already in the model: its
// `effects.<name>.uncertainty` mapping, one standard deviation per parameter
// key. diagnose refits those parameters with every candidate, like the
// body's mass properties, the standard deviations as Gaussian priors
// (diagnose/body_parameters.hpp); a fitted change beyond 3 of them is
// reported as "model parameter off". An effect added earlier with a wrong
// value is then corrected where the data can tell, not explained away by
// another effect.
//
// What can be refitted: the numbers of a key that holds one number or one
// per rod (friction, drag coefficients, sensor offsets and gains, rod mass,
// stiffness and length errors). A scalar standard deviation refits one
// common offset added to every rod's value; a list of one per rod refits
// each rod's value on its own. The frames (files, joint-compliance maps)
// refit one factor on their stiffness (by default: kFrameStiffnessUncertainty);
// the vector keys (joint positions, a drag centre) are held as given.
#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rig/effect_parameters.hpp"
#include "rig/range_scales.hpp"

namespace rigflex::rig {

struct EffectKind;  // rig/effect_kinds.hpp, which needs the rig model this is part of

struct EffectUncertainty {
  struct Item {
    std::string key;   // the parameter's key
    int rod = -1;      // the rod whose value it offsets; -1: every rod's (or the one number)
    double sigma = 0;  // standard deviation, in the parameter's unit
    std::string unit;
    double low = -INFINITY, high = INFINITY;  // the parameter's physical range
    bool low_open = false;
    double fallback = 0;       // the kind's default, where the file gives no value
    std::string name() const;  // "mass" or "mass[2]"
  };
  std::string effect;         // the spec's name
  ParameterValue parameters;  // the effect's parameters as the file gives them, `uncertainty` taken out
  int rods = 0;
  std::vector<Item> items;
  // A frame (files, joint-compliance maps): its one item is a common factor
  // on the frame's stiffness, its offset in % (rig::stiffened), as the
  // rods' stiffness is refitted (rods.uncertainty.stiffness): one number
  // for the give a frame model leaves out (bolted joints, welds, a floor).
  bool frame_stiffness = false;
};

// A frame's stiffness where the rig file states none: known to +-10 %. An FE
// model of a welded or bolted frame leaves out the give of its joints and
// its floor, and no catalogue candidate stands in for a frame the model
// already has: held as given, a frame 5 % stiffer or softer than its model
// left the large rig's clean records at 7e4 x the noise and had diagnose
// name a carrying frame or a rod length error (docs/compare.md). The rods'
// stiffness, whose error rod_compliance can stand in for, is held unless
// stated.
inline constexpr double kFrameStiffnessUncertainty = 0.1;

// Takes `uncertainty` out of an effect's parameter tree (which the effect's
// own parse then reads without it) and checks it against the kind; none if
// the tree has none, but for a frame, whose stiffness is then known to
// kFrameStiffnessUncertainty. A frame takes `{stiffness: s}` only, s the
// relative standard deviation of its stiffness (0 <= s < 1; 0 holds it as
// given: none). Throws ParameterError naming the line and key
// ("uncertainty.mass") relative to the effect. A refitted value is held
// within the key's physical range for a rig of these `scales`
// (rig/effect_ranges.hpp; unknown sizes leave the scaled ends open).
std::optional<EffectUncertainty> take_uncertainty(const EffectKind& kind, ParameterValue& tree, int rods,
                                                  const RangeScales& scales = {});

// The `uncertainty` mapping of a fitted effect's rig-file parameters
// `written` = write(theta) (rig::EffectFitting::write): each number or
// per-rod key's standard deviation propagated from the fit's (`std`, one
// per parameter of theta) to first order, over one standard deviation of
// each parameter, their correlations neglected. Keys the fit leaves
// unchanged, or changes for some rods only, get none; none at all where no
// key has one; for a frame (its fitted compliances) the relative deviation
// of a common factor on them, as `{stiffness: s}` (none where s >= 1). diagnose writes it into its effects files, so
// the effect, once added, is refitted by later fits like any value the user states.
std::optional<ParameterValue> fitted_uncertainty(const EffectKind& kind,
                                                 const std::function<ParameterValue(const Eigen::VectorXd&)>& write,
                                                 const Eigen::VectorXd& theta, const Eigen::VectorXd& std);

// The effect's parameters with delta(i) added to item i's value (a value the
// file gives as one number for every rod becomes a list where an item
// offsets one rod), kept within the parameter's physical range.
ParameterValue with_offsets(const EffectUncertainty& u, const Eigen::VectorXd& delta);

}  // namespace rigflex::rig
