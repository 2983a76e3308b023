#include "rig/record.hpp"

#include <charconv>
#include <cmath>

namespace rigflex::rig {

int RecordProvenance::line_of(long sample) const {
  if (first_sample_line <= 0 || sample < 0) return 0;
  return first_sample_line + static_cast<int>(sample);
}

int Record::rods() const { return static_cast<int>(force.cols()); }

int Record::samples() const { return static_cast<int>(t.size()); }

std::string Record::comment(const std::string& key) const {
  for (const auto& [k, v] : provenance.comments)
    if (k == key) return v;
  return "";
}

double nominal_sample_rate(const Eigen::VectorXd& t, const RecordComments& comments) {
  for (const auto& [key, value] : comments) {
    if (key != "sample_rate_hz") continue;
    double rate = 0;
    const auto r = std::from_chars(value.data(), value.data() + value.size(), rate);
    if (r.ec == std::errc() && r.ptr == value.data() + value.size() && std::isfinite(rate) && rate > 0) return rate;
    break;
  }
  if (t.size() < 2 || !(t(t.size() - 1) > t(0))) return 0.0;
  return static_cast<double>(t.size() - 1) / (t(t.size() - 1) - t(0));
}

}  // namespace rigflex::rig
