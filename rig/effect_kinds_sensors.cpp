// Effects in the measurement chain (the measure hook): the encoders' zero
// offsets and the load cells' calibration.
#include "rig/effect_kind_entries.hpp"
#include "rig/effects.hpp"

namespace rigflex::rig::kinds {
namespace {

using R = ParameterReader;

std::shared_ptr<const Effect> parse_load_cell_gain(const ParameterValue& e, const EffectParseContext& x) {
  expect_parameters(e, x, "load_cell_gain");
  if (!e["gain"].defined() && !e["offset"].defined()) R::fail(e, x.key, "needs 'gain' and/or 'offset' (N)");
  const auto n = static_cast<size_t>(x.rods);
  return std::make_shared<LoadCellGain>(e["gain"].defined() ? R::per_rod(e, "gain", x.rods) : std::vector<double>(n, 1.0),
                                        e["offset"].defined() ? R::per_rod(e, "offset", x.rods) : std::vector<double>(n, 0.0));
}

// Every encoder's offset.
EffectFitting fit_encoder_offset(const FitContext& x) {
  const int n = x.rods;
  EffectFitting f;
  f.parameters = per_rod_parameters("alpha", "rad", n, 1e-3, 0.05);
  const auto beta = per_rod_parameters("beta", "rad", n, 1e-3, 0.05);
  f.parameters.insert(f.parameters.end(), beta.begin(), beta.end());
  f.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const Effect> {
    return std::make_shared<EncoderOffset>(segment(p, 0, n), segment(p, n, n));
  };
  f.write = [n](const Eigen::VectorXd& p) {
    return ParameterValue::map()
        .set("alpha", ParameterValue::of(segment(p, 0, n)))
        .set("beta", ParameterValue::of(segment(p, n, n)));
  };
  f.advice = "calibrate the encoders' zero with the rods hanging at rest and give the offsets "
             "(effects.encoder_offset)";
  f.evidence = "a record at rest with the rods hanging still: an offset reads as a constant non-zero angle";
  return f;
}

// Every load cell's gain (as its error from 1) and offset.
EffectFitting fit_load_cell_gain(const FitContext& x) {
  const FitScales s = fit_scales(x);
  const int n = s.n;
  EffectFitting f;
  f.parameters = per_rod_parameters("gain_error", "1", n, 1e-3, 0.1);
  const auto offset = per_rod_parameters("offset", "N", n, 1e-3 * s.W, 0.1 * s.W);
  f.parameters.insert(f.parameters.end(), offset.begin(), offset.end());
  f.make = [n](const Eigen::VectorXd& p) -> std::shared_ptr<const Effect> {
    std::vector<double> gain = segment(p, 0, n);
    for (double& g : gain) g = std::max(1.0 + g, 1e-3);
    return std::make_shared<LoadCellGain>(gain, segment(p, n, n));
  };
  f.write = [n](const Eigen::VectorXd& p) {
    std::vector<double> gain = segment(p, 0, n);
    for (double& g : gain) g = 1.0 + g;
    return ParameterValue::map().set("gain", ParameterValue::of(gain)).set("offset", ParameterValue::of(segment(p, n, n)));
  };
  f.advice = "calibrate the load cells against known weights and give gain and offset (effects.load_cell_gain)";
  f.evidence = "a record with a known weight added: a gain error scales the load cells' change, an offset does not";
  return f;
}

}  // namespace

EffectKind encoder_offset() {
  EffectKind k;
  k.name = "encoder_offset";
  k.hook = EffectHook::measure;
  k.equations = "each encoder reads its angles plus a constant offset (the identifier subtracts a known one)";
  k.signature = "constant angle shifts";
  k.parameters = {
      {"alpha", ParameterShape::per_rod, "rad", -0.5, 0.5, false, "", "offset of each alpha encoder"},
      {"beta", ParameterShape::per_rod, "rad", -0.5, 0.5, false, "", "offset of each beta encoder"},
  };
  k.parse = [](const ParameterValue& e, const EffectParseContext& x) -> std::shared_ptr<const Effect> {
    expect_parameters(e, x, "encoder_offset");
    return std::make_shared<EncoderOffset>(R::per_rod(e, "alpha", x.rods), R::per_rod(e, "beta", x.rods));
  };
  k.fitted_through = "every encoder's offset";
  k.fit = fit_encoder_offset;
  return k;
}

EffectKind load_cell_gain() {
  EffectKind k;
  k.name = "load_cell_gain";
  k.hook = EffectHook::measure;
  k.equations = "load cell i reads gain_i F_i + offset_i (the identifier inverts a known one)";
  k.signature = "F' = g F + o";
  k.parameters = {
      {"gain", ParameterShape::per_rod, "1", 0.5, 2, false, "1", "gain of each load cell (`gain` and/or `offset`)"},
      {"offset", ParameterShape::per_rod, "N", -1, 1, false, "0", "offset of each load cell",
       ParameterScale::weight_per_rod},
  };
  k.parse = parse_load_cell_gain;
  k.fitted_through = "every load cell's gain and offset";
  k.fit = fit_load_cell_gain;
  return k;
}

}  // namespace rigflex::rig::kinds
