#pragma once
// The effect catalogue as one table: every effect of
// shared/spec/rig-conventions.md declared once, with its parameters (key,
// unit, physical range, shape), how it enters the equations, how a rig file
// states it (parse) and how `rigflex diagnose` fits it (fit, whose write
// gives the parameters of a fitted effect for the one YAML writer,
// rig/effect_parameters.hpp). The rig reader, the effects files, diagnose's
// candidate list and the docs' effect tables (docs/rig.md, docs/compare.md,
// checked by tests/rig/test_effect_kinds.cpp) all follow from it.
// Adding an effect: docs/extending.md.
#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rig/effect.hpp"
#include "rig/effect_parameters.hpp"
#include "rig/rig_spec.hpp"

namespace rigflex::rig {

// Which hook of rig/effect.hpp the effect acts through.
enum class EffectHook { build, add_loads, measure };
const char* hook_name(EffectHook h);

enum class ParameterShape {
  number,        // one number
  per_rod,       // a list of one number per rod, or one number for all
  per_rod_vec3,  // a list of one [x, y, z] per rod
  vec3,          // [x, y, z]
  pair,          // [x, y]
  text,          // a word from a fixed set, or a file or folder name
  integer,
  map,           // a mapping of its own (described in the effect's doc)
};

// What a parameter's physical range is stated in: absolute units, or a
// multiple of the rig's own size (rig/effect_ranges.hpp), so that a range
// that holds for a 200 kg body on 1 m rods also holds for a truck.
enum class ParameterScale {
  absolute,
  rod_length,      // L: the rods' mean length
  weight_per_rod,  // W: the body's weight over the rods
  body_mass,       // m: the body's mass
};

struct ParameterSpec {
  std::string key;
  ParameterShape shape = ParameterShape::number;
  std::string unit;                  // "1" dimensionless; "" for text and maps
  double low = -INFINITY, high = INFINITY;  // physical range of each number, in `scale`
  bool low_open = false;             // (low, ...: low itself excluded
  std::string default_value;         // "" when required or when its absence means something (see doc)
  std::string doc;                   // a few words, for the docs' table
  ParameterScale scale = ParameterScale::absolute;
};

// What a rig file's effect is read against.
struct EffectParseContext {
  std::string key;  // "effects.<name>": keys of errors are relative to it or full paths
  int rods = 0;
  const RigGeometry* geometry = nullptr;
  double body_mass = 0;  // kg: what a frame given by its joint compliance takes
  // A frame given by a frame model or a `rigflex reduce` export: io/ reads
  // the files (`fixed`: the fixed frame, else the carrying frame).
  std::function<FrameSource(bool fixed)> read_frame;
};

// What diagnose's parameterizations are scaled by: the rig being diagnosed.
struct FitContext {
  RigGeometry geometry;        // as assembled (geometry errors the model has included)
  double suspended_mass = 0;   // kg, body and the rods' moving shares
  double body_mass = 0;        // kg: what a rig file's joint-compliance frame takes (io/rig_reader)
  double weight_per_rod = 0;   // N
  double rod_length = 0;       // mean, m
  double swing_omega = 0;      // rad/s, lowest swing mode
  double joint_radius = 0;     // RMS distance of the lower joints from their centroid, m
  int rods = 0;
  std::vector<double> rod_stiffness;  // N/m per rod as assembled (the rig file's rods block); empty: rigid
  // m: the stiffest rod's stretch under its share of the weight, as
  // assembled (rigid rods: the springs that stand for them); 0: not known.
  double rod_static_stretch = 0;
};

struct FitParameter {
  std::string name, unit;
  double probe = 0;              // finite-difference step
  double low = 0, high = 0;      // plausible values
  bool non_negative = false;     // the effect cannot be built with a negative value
};

// One effect as diagnose fits it: a few parameters, a probe size for the
// finite-difference sensitivities (an effect clearly visible in the swing
// yet in its linear range) and the range in which a value is plausible.
struct EffectFitting {
  std::vector<FitParameter> parameters;
  // The effect with these parameter values (non-negative ones clamped at 0);
  // nullptr when the values amount to no effect (a compliance of zero).
  std::function<std::shared_ptr<const Effect>(const Eigen::VectorXd&)> make;
  // The rig-file parameters that state the same effect.
  std::function<ParameterValue(const Eigen::VectorXd&)> write;
  std::string advice;  // what to add to the model to capture it properly
  // A measurement that shows the effect directly: what separates it from
  // an effect that fits the same swing records as well.
  std::string evidence;
  // The fitted effect is a stand-in for a richer model (a frame's
  // quasi-static joint compliance for its FE model): what its fit leaves
  // above the noise is its own model error, which other effects fitted on
  // top of it would absorb.
  bool stand_in = false;
};

struct EffectKind {
  std::string name;           // the spec's name, the key under `effects:`
  EffectHook hook = EffectHook::build;
  std::string equations;      // how it enters the equations, in words
  std::string signature;      // how it shows in the data
  std::vector<ParameterSpec> parameters;  // every key a rig file may give (`enabled` besides)
  // The effect a rig file's parameters state; throws ParameterError.
  std::function<std::shared_ptr<const Effect>(const ParameterValue&, const EffectParseContext&)> parse;
  std::string fitted_through;  // diagnose's parameterization, in words
  std::function<EffectFitting(const FitContext&)> fit;
};

// The context in which the values of `model` itself state effect `name`:
// its rods, geometry and body mass; no frame files to read (read_frame
// throws std::logic_error). For diagnose's refits of an effect the model
// has (rig/effect_uncertainty.hpp) and the catalogue's tests.
EffectParseContext parse_context(const RigModel& model, const std::string& name);
// The same for a rig of this geometry and body mass (diagnose's candidates,
// which hold the assembled geometry); `geometry` must outlive the context.
EffectParseContext parse_context(const RigGeometry& geometry, double body_mass, const std::string& name);

// The catalogue in the spec's order.
const std::vector<EffectKind>& effect_kinds();
const EffectKind* find_effect_kind(const std::string& name);  // nullptr: none of that name
// The spec's effect names, in its order.
const std::vector<const char*>& effect_names();
std::string effect_name_list();  // "a, b, ...": for messages

// The keys a rig file may give for the effect: `enabled` and its parameters'.
std::vector<std::string> allowed_keys(const EffectKind& kind);

}  // namespace rigflex::rig
