#pragma once
// What the HTML reports of report/reports.hpp share: number formatting that
// never prints "nan" or "-0.00", the checks that a result's arrays agree in
// size before anything is drawn, and the display of mass properties. Not for
// use outside report/.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "diagnose/history_comparison.hpp"
#include "diagnose/residual_analysis.hpp"
#include "fe/mass_properties.hpp"

namespace rigflex::report::text {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline const std::vector<double> kDash{6, 3};
inline const std::vector<double> kDot{2, 3};

// ---------------------------------------------------------------- text
std::string fmt(const char* format, double v);  // "–" when not finite
std::string num(double v);                      // 4 significant digits
std::string fixed(double v, int decimals);      // fixed decimals; no "-0.00"
std::string percent(double share);
std::string yes_no(bool b);
std::string str(Eigen::Index i);
std::string plus_minus(double value, double sd, const char* format);
std::string plus_minus(double value, double sd, int decimals);
std::string joined(const std::vector<std::string>& items, const std::string& none);
// A history's name in short: the file name of its source.
std::string short_source(const std::string& source);
std::string history_label(const std::vector<std::string>& sources, int k);

// ---------------------------------------------------------------- data
std::vector<double> values(const Eigen::VectorXd& v);
std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index c);
double at(const Eigen::VectorXd& v, Eigen::Index i);  // NaN past the end
// std::invalid_argument(what) unless ok.
void require(bool ok, const std::string& what);
// Per-channel vectors: one value per channel, or none (not computed).
void check_per_channel(const Eigen::VectorXd& v, Eigen::Index channels, const std::string& name);
void check_history(const diagnose::HistoryComparison& h, Eigen::Index channels, const std::string& where);
void check_histories(const std::vector<diagnose::HistoryComparison>& hs, Eigen::Index channels, const std::string& what);
void check_analysis(const diagnose::ResidualAnalysis& a, Eigen::Index channels, const std::string& what);
std::vector<std::string> sources_of(const std::vector<diagnose::HistoryComparison>& hs);
std::string channel_unit(const std::string& channel);  // "N" for F..., else "rad"

// ---------------------------------------------------------------- mass properties
// The ten quantities of a mass-properties record, as displayed: mass, CoG in
// mm, inertia with the decimals that give the largest moment five digits
// (0.1 kg m^2 for moments of thousands, as IdentificationReport::table()).
struct Quantity {
  std::string name;
  double scale;
  int decimals;
  std::string operator()(double v) const { return fixed(scale * v, decimals); }
  std::string operator()(double v, double sd) const { return plus_minus(scale * v, scale * sd, decimals); }
};

// mass, xG, yG, zG, Jxx, Jyy, Jzz, Jxy, Jxz, Jyz
std::array<double, 10> quantities_of(const fe::MassProperties& p);
// The inertia's decimals from the largest moment of those shown.
std::array<Quantity, 10> mass_quantities(const std::vector<const fe::MassProperties*>& shown);

}  // namespace rigflex::report::text
