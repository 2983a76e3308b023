#include "rig/effect_uncertainty.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "rig/effect_kinds.hpp"
#include "rig/effect_ranges.hpp"

namespace rigflex::rig {

namespace {

using Kind = ParameterValue::Kind;

const ParameterSpec* find_spec(const EffectKind& kind, const std::string& key) {
  for (const auto& p : kind.parameters) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

std::optional<double> number_of(const std::string& text) {
  double x = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return x;
}

double standard_deviation(const ParameterValue& v, const std::string& key) {
  const double s = ParameterReader::as_number(v, key);
  if (!(s > 0)) ParameterReader::fail(v, key, "must be a positive standard deviation");
  return s;
}

// The item's entry of the effect's map, added with the kind's default where the file gives none.
ParameterValue& entry(ParameterValue& map, const EffectUncertainty::Item& it) {
  for (auto& e : map.entries) {
    if (e.key == it.key) return e.value;
  }
  map.entries.push_back({it.key, 0, ParameterValue::of(it.fallback)});
  return map.entries.back().value;
}

double within_range(const EffectUncertainty::Item& it, double x) {
  // An open lower bound (a density, a stiffness) is kept a millionth of a
  // standard deviation above it, and never above the upper one.
  const double low = std::min(it.low_open ? it.low + 1e-6 * it.sigma : it.low, it.high);
  return std::clamp(x, low, it.high);
}

// A frame is rebuilt from its files or its joint-compliance map, which a
// refit would have to reread at every probe: its numbers are held as given,
// and only a common factor on its stiffness is refitted.
bool is_frame(const EffectKind& kind) {
  return std::any_of(kind.parameters.begin(), kind.parameters.end(),
                     [](const ParameterSpec& p) { return p.shape == ParameterShape::map; });
}

EffectUncertainty frame_stiffness_uncertainty(const EffectKind& kind, double s, const ParameterValue& tree, int rods) {
  EffectUncertainty out;
  out.effect = kind.name;
  out.rods = rods;
  out.frame_stiffness = true;
  out.parameters = tree;
  EffectUncertainty::Item item;
  item.key = "stiffness";
  item.unit = "%";
  item.sigma = 100.0 * s;
  item.low = -100.0;
  item.low_open = true;
  out.items.push_back(item);
  return out;
}

// None where the file holds the frame as given ({stiffness: 0}).
std::optional<EffectUncertainty> frame_uncertainty(const EffectKind& kind, const ParameterValue& u, int key_line,
                                                   const ParameterValue& tree, int rods) {
  if (u.kind != Kind::map || u.entries.size() != 1 || u.entries.front().key != "stiffness") {
    const int line = u.kind == Kind::map && !u.entries.empty() ? u.entries.front().key_line : key_line;
    throw ParameterError(line, "uncertainty",
                         "a frame's model is held as given but for one factor on its stiffness: expected "
                         "{stiffness: s}, s its relative standard deviation (e.g. 0.15)");
  }
  const ParameterValue& v = u.entries.front().value;
  const double s = ParameterReader::as_number(v, "uncertainty.stiffness");
  if (!(s >= 0 && s < 1)) {
    ParameterReader::fail(v, "uncertainty.stiffness",
                          "must lie in [0, 1): a relative standard deviation (0 holds the frame as given)");
  }
  if (s == 0) return std::nullopt;
  return frame_stiffness_uncertainty(kind, s, tree, rods);
}

// A key's numbers: one, or one per rod; empty for anything else.
std::vector<double> numbers(const ParameterValue& v) {
  if (v.kind == Kind::scalar && v.number) return {*v.number};
  std::vector<double> out;
  if (v.kind != Kind::list) return out;
  for (const auto& x : v.items) {
    if (x.kind != Kind::scalar || !x.number) return {};
    out.push_back(*x.number);
  }
  return out;
}

// A frame's fitted compliances as one factor on its stiffness: each
// compliance c_i +- sigma_i measures a common scale of them to a relative
// sigma_i / c_i, all of them together (correlations neglected, as for the
// other kinds) to 1 / sqrt(sum (c_i / sigma_i)^2) - to first order the
// stiffness's relative deviation too. None where that reaches 1 (the fit
// does not determine the frame's size) or nothing was fitted.
std::optional<ParameterValue> frame_fitted_uncertainty(const Eigen::VectorXd& theta, const Eigen::VectorXd& std) {
  if (std.size() != theta.size()) return std::nullopt;
  double information = 0;
  for (Eigen::Index i = 0; i < theta.size(); ++i) {
    if (theta(i) > 0 && std(i) > 0 && std::isfinite(std(i))) information += (theta(i) / std(i)) * (theta(i) / std(i));
  }
  if (!(information > 1) || !std::isfinite(information)) return std::nullopt;
  return ParameterValue::map().set("stiffness", ParameterValue::of(1.0 / std::sqrt(information)));
}

}  // namespace

std::optional<ParameterValue> fitted_uncertainty(const EffectKind& kind,
                                                 const std::function<ParameterValue(const Eigen::VectorXd&)>& write,
                                                 const Eigen::VectorXd& theta, const Eigen::VectorXd& std) {
  if (is_frame(kind)) return frame_fitted_uncertainty(theta, std);
  const ParameterValue at = write(theta);
  if (at.kind != Kind::map || std.size() != theta.size()) return std::nullopt;
  std::vector<ParameterValue> moved;  // write() one standard deviation along each parameter
  for (Eigen::Index j = 0; j < theta.size(); ++j) {
    Eigen::VectorXd t = theta;
    t(j) += std(j);
    moved.push_back(write(t));
  }
  ParameterValue u = ParameterValue::map();
  for (const auto& e : at.entries) {
    const ParameterSpec* spec = find_spec(kind, e.key);
    if (!spec || (spec->shape != ParameterShape::number && spec->shape != ParameterShape::per_rod)) continue;
    const std::vector<double> x = numbers(e.value);
    if (x.empty()) continue;
    std::vector<double> var(x.size(), 0.0);
    for (const auto& m : moved) {
      const std::vector<double> y = numbers(m[e.key]);
      if (y.size() != x.size()) return std::nullopt;  // write() changes shape with its values: not linearizable
      for (size_t i = 0; i < x.size(); ++i) var[i] += (y[i] - x[i]) * (y[i] - x[i]);
    }
    std::vector<double> sigma;
    for (double v : var) sigma.push_back(std::sqrt(v));
    if (!std::all_of(sigma.begin(), sigma.end(), [](double s) { return s > 0 && std::isfinite(s); })) continue;
    u.set(e.key, sigma.size() == 1 && e.value.kind == Kind::scalar ? ParameterValue::of(sigma.front())
                                                                   : ParameterValue::of(sigma));
  }
  if (u.entries.empty()) return std::nullopt;
  return u;
}

std::string EffectUncertainty::Item::name() const { return rod < 0 ? key : key + "[" + std::to_string(rod) + "]"; }

std::optional<EffectUncertainty> take_uncertainty(const EffectKind& kind, ParameterValue& tree, int rods,
                                                  const RangeScales& scales) {
  if (tree.kind != Kind::map) return std::nullopt;
  const auto at = std::find_if(tree.entries.begin(), tree.entries.end(),
                               [](const ParameterEntry& e) { return e.key == "uncertainty"; });
  if (at == tree.entries.end()) {
    if (is_frame(kind)) return frame_stiffness_uncertainty(kind, kFrameStiffnessUncertainty, tree, rods);
    return std::nullopt;
  }
  const ParameterValue u = at->value;
  const int key_line = at->key_line;
  tree.entries.erase(at);
  if (is_frame(kind)) return frame_uncertainty(kind, u, key_line, tree, rods);
  if (u.kind != Kind::map || u.entries.empty()) {
    ParameterReader::fail(u.line ? u : tree, "uncertainty",
                          "expected a mapping of parameter key to standard deviation, e.g. {mass: 0.5}");
  }
  EffectUncertainty out;
  out.effect = kind.name;
  out.rods = rods;
  for (const auto& e : u.entries) {
    const std::string key = "uncertainty." + e.key;
    const ParameterSpec* spec = find_spec(kind, e.key);
    if (!spec) throw ParameterError(e.key_line, key, "'" + e.key + "' is not a parameter of " + kind.name);
    if (spec->shape != ParameterShape::number && spec->shape != ParameterShape::per_rod) {
      throw ParameterError(e.key_line, key,
                           "only keys of one number or one per rod are refitted; '" + e.key + "' is held as given");
    }
    const std::optional<double> fallback = number_of(spec->default_value);
    if (!tree[e.key].defined() && !fallback) {
      throw ParameterError(e.key_line, key, "the effect gives no '" + e.key + "' to refit");
    }
    EffectUncertainty::Item item;
    item.fallback = fallback.value_or(0.0);
    item.key = e.key;
    item.unit = spec->unit;
    item.low = range_low(*spec, scales);
    item.high = range_high(*spec, scales);
    item.low_open = spec->low_open;
    if (e.value.kind == Kind::list) {
      if (spec->shape != ParameterShape::per_rod) ParameterReader::fail(e.value, key, "expected a number");
      if (static_cast<int>(e.value.items.size()) != rods) {
        ParameterReader::fail(e.value, key,
                              "needs one standard deviation per rod (" + std::to_string(rods) +
                                  ") or one for all, got " + std::to_string(e.value.items.size()));
      }
      for (int i = 0; i < rods; ++i) {
        item.rod = i;
        item.sigma = standard_deviation(e.value.items[static_cast<size_t>(i)], key);
        out.items.push_back(item);
      }
    } else {
      item.sigma = standard_deviation(e.value, key);
      out.items.push_back(item);
    }
  }
  out.parameters = tree;
  return out;
}

ParameterValue with_offsets(const EffectUncertainty& u, const Eigen::VectorXd& delta) {
  if (u.frame_stiffness) throw std::logic_error("with_offsets: a frame's stiffness factor scales the built frame");
  ParameterValue p = u.parameters;
  for (size_t i = 0; i < u.items.size(); ++i) {
    const EffectUncertainty::Item& it = u.items[i];
    const double d = delta(static_cast<Eigen::Index>(i));
    ParameterValue& v = entry(p, it);
    if (it.rod >= 0 && v.kind == Kind::scalar) {
      // One value for every rod, of which one rod's is refitted: a list from here.
      v = ParameterValue::list(std::vector<ParameterValue>(static_cast<size_t>(u.rods), v));
    }
    auto offset = [&](ParameterValue& x) { x = ParameterValue::of(within_range(it, x.number.value_or(0.0) + d)); };
    if (v.kind == Kind::scalar) {
      offset(v);
    } else if (it.rod >= 0) {
      offset(v.items[static_cast<size_t>(it.rod)]);
    } else {
      for (auto& x : v.items) offset(x);
    }
  }
  return p;
}

}  // namespace rigflex::rig
