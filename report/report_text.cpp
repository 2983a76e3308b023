#include "report/report_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "identify/mass_statistics.hpp"

namespace rigflex::report::text {

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}
std::string num(double v) { return fmt("%.4g", v); }

// Fixed decimals; no "-0.00".
std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  std::string s = b;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}
std::string percent(double share) { return fmt("%.1f %%", 100 * share); }
std::string yes_no(bool b) { return b ? "yes" : "no"; }
std::string str(Eigen::Index i) { return std::to_string(i); }

std::string plus_minus(double value, double sd, const char* format) {
  return std::isfinite(sd) ? fmt(format, value) + " ± " + fmt(format, sd) : fmt(format, value);
}
std::string plus_minus(double value, double sd, int decimals) {
  return std::isfinite(sd) ? fixed(value, decimals) + " ± " + fixed(sd, decimals) : fixed(value, decimals);
}

std::string joined(const std::vector<std::string>& items, const std::string& none) {
  if (items.empty()) return none;
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// A history's name in short: the file name of its source.
std::string short_source(const std::string& source) {
  const std::string f = std::filesystem::path(source).filename().string();
  return f.empty() ? source : f;
}

std::string history_label(const std::vector<std::string>& sources, int k) {
  std::string s = "h" + std::to_string(k + 1);
  if (k >= 0 && static_cast<size_t>(k) < sources.size() && !sources[static_cast<size_t>(k)].empty())
    s += " " + short_source(sources[static_cast<size_t>(k)]);
  return s;
}

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }
std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index c) { return values(m.col(c)); }
double at(const Eigen::VectorXd& v, Eigen::Index i) { return i < v.size() ? v(i) : kNaN; }

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Per-channel vectors: one value per channel, or none (not computed).
void check_per_channel(const Eigen::VectorXd& v, Eigen::Index channels, const std::string& name) {
  require(v.size() == 0 || v.size() == channels,
          name + " has " + str(v.size()) + " values for " + str(channels) + " channels");
}

void check_history(const diagnose::HistoryComparison& h, Eigen::Index channels, const std::string& where) {
  const Eigen::MatrixXd& m = h.measured();
  require(m.cols() == channels, where + ": measured has " + str(m.cols()) + " channels, expected " + str(channels));
  require(m.rows() == h.t().size(), where + ": " + str(h.t().size()) + " times for " + str(m.rows()) + " samples");
  require(h.model.rows() == m.rows() && h.model.cols() == m.cols(),
          where + ": model is " + str(h.model.rows()) + " x " + str(h.model.cols()) + ", measured " + str(m.rows()) +
              " x " + str(m.cols()));
  check_per_channel(h.nrmse, channels, where + ": nrmse");
  check_per_channel(h.raw_nrmse, channels, where + ": raw_nrmse");
  check_per_channel(h.target.sigma, channels, where + ": noise (target.sigma)");
}

void check_histories(const std::vector<diagnose::HistoryComparison>& hs, Eigen::Index channels, const std::string& what) {
  require(channels % 3 == 0, what + ": " + str(channels) + " channels, not 3 per rod (F, alpha, beta)");
  for (size_t k = 0; k < hs.size(); ++k)
    check_history(hs[k], channels, what + ": history " + std::to_string(k + 1) + " (" + hs[k].source + ")");
}

void check_analysis(const diagnose::ResidualAnalysis& a, Eigen::Index channels, const std::string& what) {
  check_per_channel(a.noise, channels, what + ": analysis.noise");
  check_per_channel(a.noise_ratio, channels, what + ": analysis.noise_ratio");
  check_per_channel(a.static_offset, channels, what + ": analysis.static_offset");
  check_per_channel(a.offset_in_noise, channels, what + ": analysis.offset_in_noise");
  check_per_channel(a.channel_share, channels, what + ": analysis.channel_share");
  for (const auto& s : a.correlations) check_per_channel(s.per_channel, channels, what + ": correlation " + s.state);
  require(a.trend_t.size() == a.trend_nrmse.size(), what + ": analysis.trend_t has " + std::to_string(a.trend_t.size()) +
                                                        " values, trend_nrmse " + std::to_string(a.trend_nrmse.size()));
  const diagnose::ResidualSpectra& s = a.spectra;
  const Eigen::Index f = s.frequency_hz.size();
  for (const auto* v : {&s.residual_force, &s.residual_angle, &s.measured_force, &s.measured_angle})
    require(v->size() == f, what + ": a spectrum has " + str(v->size()) + " values for " + str(f) + " frequencies");
}

std::vector<std::string> sources_of(const std::vector<diagnose::HistoryComparison>& hs) {
  std::vector<std::string> s;
  for (const auto& h : hs) s.push_back(h.source);
  return s;
}

std::string channel_unit(const std::string& channel) { return channel.rfind('F', 0) == 0 ? "N" : "rad"; }
std::array<double, 10> quantities_of(const fe::MassProperties& p) {
  const auto c = identify::mass_components(p);
  std::array<double, 10> q{p.mass};
  std::copy(c.begin(), c.end(), q.begin() + 1);
  return q;
}

std::array<Quantity, 10> mass_quantities(const std::vector<const fe::MassProperties*>& shown) {
  double largest = 0;
  for (const auto* p : shown)
    for (int i = 0; i < 3; ++i)
      if (std::isfinite(p->inertia(i, i))) largest = std::max(largest, std::abs(p->inertia(i, i)));
  const int d = largest > 0 ? std::clamp(4 - static_cast<int>(std::floor(std::log10(largest))), 0, 9) : 4;
  return {{{"m (kg)", 1, 2},
           {"xG (mm)", 1e3, 2},
           {"yG (mm)", 1e3, 2},
           {"zG (mm)", 1e3, 2},
           {"Jxx (kg m²)", 1, d},
           {"Jyy (kg m²)", 1, d},
           {"Jzz (kg m²)", 1, d},
           {"Jxy (kg m²)", 1, d},
           {"Jxz (kg m²)", 1, d},
           {"Jyz (kg m²)", 1, d}}};
}

}  // namespace rigflex::report::text
