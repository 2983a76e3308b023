#include "io/measurement_reader.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "io/file_text.hpp"
#include "io/measurement_text.hpp"

namespace rigflex::io {
namespace {

namespace fs = std::filesystem;
using namespace measurement_text;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Where each needed quantity is among the header's fields.
struct Layout {
  std::vector<std::string_view> names;  // the header's fields, trimmed
  size_t time = 0;
  std::vector<size_t> force, alpha, beta;  // per rod
};

// The fields of one quantity found in the header, by rod. A map, not a
// vector indexed by rod: a column "F99999999" must not size anything.
using Found = std::map<int, size_t>;

class MeasurementFileReader {
 public:
  MeasurementFileReader(std::string file, RodRule rule) : file_(std::move(file)), rule_(std::move(rule)) {}

  rig::Record read(std::string_view text) {
    // A UTF-8 byte order mark, as spreadsheet programs on Windows write one.
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    lines_ = split_lines(text);
    rig::Record h;
    const size_t header = read_comments(h);
    const Layout layout = read_header(header);
    read_samples(header, layout, h);
    check_columns(header, layout, h);
    h.provenance.warnings = channel_warnings(header, layout, h);
    h.provenance.file = file_;
    // Sample k is on line header + 2 + k (1-based): the reader refuses blank lines among the samples.
    h.provenance.first_sample_line = static_cast<int>(header + 2);
    h.sample_rate_hz = rig::nominal_sample_rate(h.t, h.provenance.comments);
    if (auto w = rate_warning(h)) h.provenance.warnings.push_back(*w);
    return h;
  }

 private:
  [[noreturn]] void fail(size_t line_index, const std::string& key, const std::string& message) const {
    throw InputError(file_, static_cast<int>(line_index + 1), key, message);
  }

  // The leading "# key: value" lines; returns the index of the header line.
  // Blank lines among them are skipped. A '#' line without ':' (or with
  // nothing before it) is a free remark and is not kept: only key/value
  // comments have a meaning to the tools.
  size_t read_comments(rig::Record& h) const {
    size_t i = 0;
    for (; i < lines_.size(); ++i) {
      const std::string_view line = trim(lines_[i]);
      if (line.empty()) continue;
      if (line.front() != '#') break;
      if (!valid_utf8(line)) fail(i, "", "the comment is not valid UTF-8 (measurement files are UTF-8)");
      const std::string_view body = line.substr(1);
      const auto colon = body.find(':');
      if (colon == std::string_view::npos) continue;
      const std::string_view key = trim(body.substr(0, colon));
      if (key.empty()) continue;
      h.provenance.comments.emplace_back(std::string(key), std::string(trim(body.substr(colon + 1))));
    }
    if (i == lines_.size())
      throw InputError(file_, static_cast<int>(std::max<size_t>(lines_.size(), 1)), "",
                       lines_.empty() ? "the file is empty" : "no header line after the comments");
    return i;
  }

  Layout read_header(size_t line) const {
    Layout layout;
    layout.names = split_fields(lines_[line]);
    const auto& names = layout.names;
    std::optional<size_t> time;
    Found force, alpha, beta;
    for (size_t f = 0; f < names.size(); ++f) {
      const Column c = classify(names[f]);
      if (c.quantity == Quantity::other) continue;
      std::optional<size_t> earlier;
      if (c.quantity == Quantity::time) {
        earlier = std::exchange(time, f);
      } else {
        Found& found = c.quantity == Quantity::force ? force : c.quantity == Quantity::alpha ? alpha : beta;
        if (const auto [it, added] = found.emplace(c.rod, f); !added) earlier = it->second;
      }
      if (earlier)
        fail(line, std::string(names[f]),
             "duplicated column (fields " + std::to_string(*earlier + 1) + " and " + std::to_string(f + 1) +
                 " of the header)");
    }
    if (!time) missing(line, names, "t");
    layout.time = *time;
    const int rods = rod_count(line, names, force);
    layout.force = required(line, names, force, Quantity::force, rods);
    layout.alpha = required(line, names, alpha, Quantity::alpha, rods);
    layout.beta = required(line, names, beta, Quantity::beta, rods);
    refuse_extra(line, alpha, Quantity::alpha, rods);
    refuse_extra(line, beta, Quantity::beta, rods);
    return layout;
  }

  [[noreturn]] void missing(size_t line, const std::vector<std::string_view>& names, const std::string& name) const {
    std::string message = "missing column";
    // Say why a header that looks right is not: the names are exact and the separator is ','.
    for (const auto& n : names)
      if (n != name && lower(n) == lower(name))
        message += " (column names are case-sensitive; found " + quoted(n) + ")";
    if (names.size() == 1 && names[0].find_first_of(";\t") != std::string_view::npos)
      message += " (the header has no ','; fields must be comma separated)";
    fail(line, name, message);
  }

  // n: F1..Fn present without a gap, as many as the rule wants.
  int rod_count(size_t line, const std::vector<std::string_view>& names, const Found& force) const {
    int rods = 0;
    while (force.count(rods + 1)) ++rods;
    if (rods == 0 || force.size() > static_cast<size_t>(rods))
      missing(line, names, column_name(Quantity::force, rods + 1));
    if (rule_.count != 0 && rods != rule_.count) {
      const int first_wrong = std::min(rods, rule_.count) + 1;
      fail(line, column_name(Quantity::force, first_wrong),
           "the file has " + std::to_string(rods) + " rods (F1..F" + std::to_string(rods) + ") but " +
               std::to_string(rule_.count) + " are expected" + rule_.origin);
    }
    return rods;
  }

  std::vector<size_t> required(size_t line, const std::vector<std::string_view>& names, const Found& found,
                               Quantity q, int rods) const {
    std::vector<size_t> out;
    for (int k = 1; k <= rods; ++k) {
      const auto it = found.find(k);
      if (it == found.end()) missing(line, names, column_name(q, k));
      out.push_back(it->second);
    }
    return out;
  }

  // An angle of a rod without a force column means the file and the rod count disagree.
  void refuse_extra(size_t line, const Found& found, Quantity q, int rods) const {
    const auto extra = found.upper_bound(rods);
    if (extra != found.end())
      fail(line, column_name(q, extra->first),
           "no rod " + std::to_string(extra->first) + ": the file has force columns F1..F" + std::to_string(rods));
  }

  // Values a rig cannot produce, and sensors that produced nothing. An
  // angle past 90 degrees is a rod above its joint: the value is in degrees
  // (a 3 degree swing reads 3.0); a force past 1e8 N is ten thousand
  // tonnes. A column that holds one value over the whole record is a dead
  // or disconnected channel (a real sensor always shows its noise): read as
  // data it gave a negative Jxx, so it is refused, naming what it carried.
  void check_columns(size_t header, const Layout& layout, const rig::Record& h) const {
    constexpr double kMaxAngle = 1.5707963267948966, kMaxForce = 1e8;
    const auto& names = layout.names;
    const Eigen::Index rows = h.t.size();
    auto check = [&](const Eigen::MatrixXd& x, const std::vector<size_t>& columns, double limit, const char* unit,
                     const char* hint, const char* carries) {
      for (Eigen::Index k = 0; k < x.cols(); ++k) {
        const std::string name(names[columns[static_cast<size_t>(k)]]);
        Eigen::Index at = 0;
        if (x.col(k).cwiseAbs().maxCoeff(&at) > limit) {
          fail(header + 1 + static_cast<size_t>(at), name,
               "value " + number_text(x(at, k)) + " is beyond what the rig can measure (|x| <= " + number_text(limit) +
                   " " + unit + ")" + hint);
        }
        if (rows >= 10 && x.col(k).maxCoeff() == x.col(k).minCoeff()) {
          fail(header + 1, name,
               "the column holds " + number_text(x(0, k)) + " in all " + std::to_string(rows) +
                   " samples: a dead or disconnected sensor (a live one shows its noise); without it " + carries +
                   " cannot be measured");
        }
      }
    };
    check(h.force, layout.force, kMaxForce, "N", ": are the forces in N?",
          "the rod's force, and so the mass properties,");
    check(h.alpha, layout.alpha, kMaxAngle, "rad", ": angles are in rad, not degrees",
          "the rod's swing about its encoder axis, and so the body's motion,");
    check(h.beta, layout.beta, kMaxAngle, "rad", ": angles are in rad, not degrees",
          "the rod's swing across its encoder axis, and so the body's motion,");
  }

  // A "sample_rate_hz" comment the time stamps contradict (beyond 1 %: a
  // logger's clock drifts by ppm): the tools go by the stamps, so the
  // comment is only a sign of a file from another run or a wrong column t.
  std::optional<std::string> rate_warning(const rig::Record& h) const {
    const Eigen::Index n = h.t.size();
    if (n < 2 || h.comment("sample_rate_hz").empty()) return std::nullopt;
    const double stamps = rig::nominal_sample_rate(h.t, {});
    if (std::abs(h.sample_rate_hz - stamps) <= 0.01 * stamps) return std::nullopt;
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "the comment gives sample_rate_hz: %s but the time stamps (column t) %.6g Hz; the stamps are used",
                  h.comment("sample_rate_hz").c_str(), stamps);
    return std::string(msg);
  }

  // A channel that holds one value for a long stretch: at its extreme a
  // sensor clipped at its range (for 0.25 s or more: a swing's turning
  // point, quantized to 17 bits, stays on one count for about 0.05 s), else
  // stuck (for 1 s or more). Doubtful, not wrong - a warning.
  std::vector<std::string> channel_warnings(size_t header, const Layout& layout, const rig::Record& h) const {
    std::vector<std::string> out;
    const Eigen::Index n = h.t.size();
    if (n < 10) return out;
    const double dt = (h.t(n - 1) - h.t(0)) / static_cast<double>(n - 1);
    auto look = [&](const Eigen::MatrixXd& x, const std::vector<size_t>& columns) {
      for (Eigen::Index k = 0; k < x.cols(); ++k) {
        Eigen::Index best = 0, best_start = 0;
        for (Eigen::Index i = 0, start = 0; i < n; ++i) {
          if (i > 0 && x(i, k) != x(i - 1, k)) start = i;
          if (i - start + 1 > best) best = i - start + 1, best_start = start;
        }
        const double v = x(best_start, k), seconds = static_cast<double>(best - 1) * dt;
        const bool extreme = v == x.col(k).maxCoeff() || v == x.col(k).minCoeff();
        if (!(seconds >= (extreme ? 0.25 : 1.0))) continue;
        const std::string name(layout.names[columns[static_cast<size_t>(k)]]);
        char msg[256];
        std::snprintf(msg, sizeof msg, "line %zu: %s holds %s for %.3g s (%ld samples)%s",
                      header + 2 + static_cast<size_t>(best_start), name.c_str(), number_text(v).c_str(), seconds,
                      static_cast<long>(best),
                      extreme ? ", at its extreme: clipped by the sensor's range?" : ": a stuck sensor?");
        out.emplace_back(msg);
      }
    };
    look(h.force, layout.force);
    look(h.alpha, layout.alpha);
    look(h.beta, layout.beta);
    return out;
  }

  void read_samples(size_t header, const Layout& layout, rig::Record& h) const {
    const auto& names = layout.names;
    // Blank lines at the end are tolerated (editors and loggers leave them).
    size_t end = lines_.size();
    while (end > header + 1 && is_blank_line(lines_[end - 1])) --end;
    if (end == header + 1) fail(header, "", "no data rows after the header");

    const size_t rows = end - header - 1;
    const size_t rods = layout.force.size();
    std::vector<double> t(rows), force(rows * rods), alpha(rows * rods), beta(rows * rods);
    std::vector<std::string_view> fields;
    // Where each field goes in a row's slots (t, F1..Fn, alpha1..n, beta1..n); -1: ignored column.
    std::vector<int> target(names.size(), -1);
    target[layout.time] = 0;
    for (size_t k = 0; k < rods; ++k) {
      target[layout.force[k]] = static_cast<int>(1 + k);
      target[layout.alpha[k]] = static_cast<int>(1 + rods + k);
      target[layout.beta[k]] = static_cast<int>(1 + 2 * rods + k);
    }
    std::vector<double> slot(1 + 3 * rods);
    for (size_t r = 0; r < rows; ++r) {
      const size_t line = header + 1 + r;
      if (fast_row(lines_[line], target, slot) && (r == 0 || slot[0] > t[r - 1])) {
        t[r] = slot[0];
        for (size_t k = 0; k < rods; ++k) {
          force[r * rods + k] = slot[1 + k];
          alpha[r * rods + k] = slot[1 + rods + k];
          beta[r * rods + k] = slot[1 + 2 * rods + k];
        }
        continue;
      }
      if (is_blank_line(lines_[line])) fail(line, "", "blank line among the samples");
      split_fields(lines_[line], fields);
      check_field_count(line, fields, names);
      auto value = [&](size_t field) { return number(line, names[field], fields[field]); };
      t[r] = value(layout.time);
      // `line` is this row's 0-based index, so also the previous row's 1-based number.
      if (r > 0 && !(t[r] > t[r - 1]))
        fail(line, "t", "time " + quoted(fields[layout.time]) + " is not after the previous sample's " +
                            number_text(t[r - 1]) + " (line " + std::to_string(line) +
                            "): time must strictly increase");
      for (size_t k = 0; k < rods; ++k) {
        force[r * rods + k] = value(layout.force[k]);
        alpha[r * rods + k] = value(layout.alpha[k]);
        beta[r * rods + k] = value(layout.beta[k]);
      }
    }
    const auto n = static_cast<Eigen::Index>(rows), m = static_cast<Eigen::Index>(rods);
    h.t = Eigen::Map<const Eigen::VectorXd>(t.data(), n);
    h.force = Eigen::Map<const RowMajor>(force.data(), n, m);
    h.alpha = Eigen::Map<const RowMajor>(alpha.data(), n, m);
    h.beta = Eigen::Map<const RowMajor>(beta.data(), n, m);
  }

  // The common row, read without the checks' bookkeeping: every field
  // exactly a number (no blanks, no '+'), finite, the header's field count.
  // Anything else returns false and the row is read again by the checked
  // path, which accepts what the contract allows and names what it does not.
  static bool fast_row(std::string_view line, const std::vector<int>& target, std::vector<double>& slot) {
    const char* p = line.data();
    const char* const end = p + line.size();
    const size_t fields = target.size();
    for (size_t f = 0; f < fields; ++f) {
      const char* stop = static_cast<const char*>(std::memchr(p, ',', static_cast<size_t>(end - p)));
      if (f + 1 < fields) {
        if (!stop) return false;
      } else {
        if (stop) return false;
        stop = end;
      }
      if (target[f] >= 0) {
        double v = 0.0;
        const auto res = std::from_chars(p, stop, v);
        if (p == stop || res.ec != std::errc() || res.ptr != stop || !std::isfinite(v)) return false;
        slot[static_cast<size_t>(target[f])] = v;
      }
      p = stop + 1;
    }
    return true;
  }

  void check_field_count(size_t line, const std::vector<std::string_view>& fields,
                         const std::vector<std::string_view>& names) const {
    if (fields.size() == names.size()) return;
    std::string message = std::to_string(fields.size()) + " fields but the header has " + std::to_string(names.size());
    if (fields.size() > names.size()) {
      // The likeliest cause: numbers written with a decimal comma.
      fail(line, "", message + " (numbers need a '.' decimal point; ',' separates fields)");
    }
    fail(line, std::string(names[fields.size()]), message + ": this column's value is missing");
  }

  // from_chars, not strtod: independent of the locale. A leading '+' is
  // accepted (some loggers write one); nan and inf are refused, since no
  // measured value is either.
  double number(size_t line, std::string_view column, std::string_view text) const {
    auto bad = [&](const std::string& why) { fail(line, std::string(column), why); };
    if (text.empty()) bad("empty value");
    std::string_view digits = text;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
    const char* end = digits.data() + digits.size();
    double v = 0.0;
    const auto r = std::from_chars(digits.data(), end, v);
    if (r.ec == std::errc::result_out_of_range && r.ptr == end)
      bad("value " + quoted(text) + " is outside the range of a double");
    if (r.ec != std::errc() || r.ptr != end) bad("value " + quoted(text) + " is not a number");
    if (!std::isfinite(v)) bad("value " + quoted(text) + " is not finite");
    return v;
  }

  std::string file_;
  RodRule rule_;
  std::vector<std::string_view> lines_;
};

rig::Record parse_text(std::string_view text, const std::string& file, RodRule rule) {
  if (rule.count < 0) throw std::invalid_argument("time history: expected_rods must be 0 (any) or positive");
  return MeasurementFileReader(file, std::move(rule)).read(text);
}

std::string read_all(std::istream& in, const std::string& file) {
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, 0, "", "cannot read the file");
  return text;
}

}  // namespace

rig::Record read_measurement_file(const fs::path& file, RodRule rule) {
  return parse_text(read_file_text(file), file.string(), std::move(rule));
}

rig::Record read_record_csv(const fs::path& file, int expected_rods) {
  return read_measurement_file(file, {expected_rods, ""});
}

rig::Record parse_record_csv(std::istream& in, const std::string& file_name, int expected_rods) {
  return parse_text(read_all(in, file_name), file_name, {expected_rods, ""});
}

}  // namespace rigflex::io
