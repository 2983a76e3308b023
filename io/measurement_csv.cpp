#include "io/measurement_csv.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "io/atomic_file.hpp"

namespace rigflex::io {
namespace {

namespace fs = std::filesystem;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// ---------------------------------------------------------------- text helpers

bool blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

bool is_blank_line(std::string_view s) { return trim(s).empty(); }

// Lines without their terminator; "\r\n" and "\n" both end a line (loggers on
// Windows write the former).
std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const auto end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

// Comma separated, blanks around each field trimmed. No quoting: the contract
// has none, and neither numbers nor column names need it.
// Into `fields` (cleared first), so that a reader splitting thousands of rows reuses one vector.
void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  while (true) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return;
    line.remove_prefix(comma + 1);
  }
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  split_fields(line, fields);
  return fields;
}

// A field as shown in a message; long garbage is cut so the message stays readable.
std::string quoted(std::string_view s) {
  constexpr size_t kShown = 40;
  return "'" + std::string(s.substr(0, kShown)) + (s.size() > kShown ? "...'" : "'");
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool valid_utf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    size_t extra = 0;
    unsigned min = 0;
    unsigned cp = 0;
    if (c < 0x80) extra = 0, cp = c;
    else if ((c & 0xE0) == 0xC0) extra = 1, cp = c & 0x1Fu, min = 0x80;
    else if ((c & 0xF0) == 0xE0) extra = 2, cp = c & 0x0Fu, min = 0x800;
    else if ((c & 0xF8) == 0xF0) extra = 3, cp = c & 0x07u, min = 0x10000;
    else return false;
    if (extra > 0 && i + extra >= s.size()) return false;
    for (size_t k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3Fu);
    }
    // Overlong forms, UTF-16 surrogates and values beyond Unicode are not UTF-8.
    if (cp < min || (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF) return false;
    i += extra + 1;
  }
  return true;
}

// The shortest decimal that reads back as the same double (to_chars without a
// precision), so files are exact, as short as can be and deterministic.
void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

std::string number_text(double v) {
  std::string s;
  append_number(s, v);
  return s;
}

// ---------------------------------------------------------------- column names

enum class Quantity { time, force, alpha, beta, other };

struct Column {
  Quantity quantity = Quantity::other;
  int rod = 0;  // 1-based, for force, alpha and beta
};

// Exact names only: "t", "F<k>", "alpha<k>", "beta<k>" with k written without
// leading zeros. Anything else ("T", "F01", "time") is an unknown column,
// which the contract says readers ignore.
Column classify(std::string_view name) {
  if (name == "t") return {Quantity::time, 0};
  for (const auto& [prefix, quantity] : {std::pair<std::string_view, Quantity>{"F", Quantity::force},
                                         {"alpha", Quantity::alpha},
                                         {"beta", Quantity::beta}}) {
    if (name.size() <= prefix.size() || name.substr(0, prefix.size()) != prefix) continue;
    const std::string_view digits = name.substr(prefix.size());
    if (digits.front() < '1' || digits.front() > '9') return {};
    int rod = 0;
    const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), rod);
    if (r.ec != std::errc() || r.ptr != digits.data() + digits.size()) return {};
    return {quantity, rod};
  }
  return {};
}

std::string column_name(Quantity q, int rod) {
  switch (q) {
    case Quantity::time: return "t";
    case Quantity::force: return "F" + std::to_string(rod);
    case Quantity::alpha: return "alpha" + std::to_string(rod);
    case Quantity::beta: return "beta" + std::to_string(rod);
    case Quantity::other: break;
  }
  return "";
}

// ---------------------------------------------------------------- reading

// What the rod count must be: `count` = 0 for any; `origin` says where the
// expectation comes from, for the message (" as in h1.csv").
struct RodRule {
  int count = 0;
  std::string origin;
};

// Where each needed quantity is among the header's fields.
struct Layout {
  std::vector<std::string_view> names;  // the header's fields, trimmed
  size_t time = 0;
  std::vector<size_t> force, alpha, beta;  // per rod
};

// The fields of one quantity found in the header, by rod. A map, not a
// vector indexed by rod: a column "F99999999" must not size anything.
using Found = std::map<int, size_t>;

class Reader {
 public:
  Reader(std::string file, RodRule rule) : file_(std::move(file)), rule_(std::move(rule)) {}

  TimeHistory read(std::string_view text) {
    // A UTF-8 byte order mark, as spreadsheet programs on Windows write one.
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    lines_ = split_lines(text);
    TimeHistory h;
    const size_t header = read_comments(h);
    const Layout layout = read_header(header);
    read_samples(header, layout, h);
    h.header_line = static_cast<int>(header + 1);
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
  size_t read_comments(TimeHistory& h) const {
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
      h.comments.emplace_back(std::string(key), std::string(trim(body.substr(colon + 1))));
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

  void read_samples(size_t header, const Layout& layout, TimeHistory& h) const {
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

TimeHistory parse_text(std::string_view text, const std::string& file, RodRule rule) {
  if (rule.count < 0) throw std::invalid_argument("time history: expected_rods must be 0 (any) or positive");
  return Reader(file, std::move(rule)).read(text);
}

std::string read_all(std::istream& in, const std::string& file) {
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, 0, "", "cannot read the file");
  return text;
}

TimeHistory read_file(const fs::path& file, RodRule rule) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the file");
  // One read of the whole file: a set of 15 s logs is megabytes, and the
  // character-wise stream iterator took most of the reading time.
  std::string text;
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (!ec) {
    text.resize(static_cast<size_t>(size));
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<size_t>(in.gcount()));
    if (in.bad()) throw InputError(file.string(), 0, "", "cannot read the file");
  } else {
    text = read_all(in, file.string());
  }
  return parse_text(text, file.string(), std::move(rule));
}

// ---------------------------------------------------------------- writing

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument("time history: " + what); }

void check_sizes(const TimeHistory& h) {
  const Eigen::Index n = h.force.cols(), rows = h.t.size();
  if (rows == 0) refuse("no samples");
  if (n == 0) refuse("no rods (force has no columns)");
  for (const auto& [A, name] : {std::pair<const Eigen::MatrixXd*, const char*>{&h.force, "force"},
                                {&h.alpha, "alpha"},
                                {&h.beta, "beta"}})
    if (A->rows() != rows || A->cols() != n)
      refuse(std::string(name) + " is " + std::to_string(A->rows()) + " x " + std::to_string(A->cols()) +
             ", expected " + std::to_string(rows) + " x " + std::to_string(n) + " (samples x rods)");
}

void check_values(const TimeHistory& h) {
  auto sample = [](Eigen::Index i) { return " of sample " + std::to_string(i + 1); };
  for (Eigen::Index i = 0; i < h.t.size(); ++i) {
    if (!std::isfinite(h.t(i))) refuse("t" + sample(i) + " is " + number_text(h.t(i)));
    if (i > 0 && !(h.t(i) > h.t(i - 1)))
      refuse("t" + sample(i) + " (" + number_text(h.t(i)) + ") is not after the previous sample's (" +
             number_text(h.t(i - 1)) + "): time must strictly increase");
  }
  for (const auto& [A, q] : {std::pair<const Eigen::MatrixXd*, Quantity>{&h.force, Quantity::force},
                             {&h.alpha, Quantity::alpha},
                             {&h.beta, Quantity::beta}})
    for (Eigen::Index k = 0; k < A->cols(); ++k)
      for (Eigen::Index i = 0; i < A->rows(); ++i)
        if (!std::isfinite((*A)(i, k)))
          refuse(column_name(q, static_cast<int>(k + 1)) + sample(i) + " is " + number_text((*A)(i, k)));
}

// Each comment must come back from its "# key: value" line as itself.
void check_comments(const TimeHistory& h) {
  for (const auto& [key, value] : h.comments) {
    const std::string which = "comment '" + key + "'";
    if (key.empty()) refuse("a comment has an empty key");
    if (key.find(':') != std::string::npos) refuse(which + ": the key contains ':'");
    for (const std::string* s : {&key, &value}) {
      if (s->find_first_of("\r\n") != std::string::npos) refuse(which + ": a line break in the key or value");
      if (trim(*s) != *s) refuse(which + ": blanks at the start or end of the key or value");
      if (!valid_utf8(*s)) refuse(which + ": not valid UTF-8");
    }
  }
}

// ---------------------------------------------------------------- folders

// Digit runs compare by value, everything else byte by byte, so h2 < h10.
int natural_compare(std::string_view a, std::string_view b) {
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      size_t ie = i, je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      std::string_view x = a.substr(i, ie - i), y = b.substr(j, je - j);
      while (x.size() > 1 && x.front() == '0') x.remove_prefix(1);
      while (y.size() > 1 && y.front() == '0') y.remove_prefix(1);
      if (x.size() != y.size()) return x.size() < y.size() ? -1 : 1;
      if (const int c = x.compare(y); c != 0) return c;
      i = ie, j = je;
      continue;
    }
    if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]) ? -1 : 1;
    ++i, ++j;
  }
  if (i < a.size()) return 1;
  if (j < b.size()) return -1;
  return 0;
}

// Equal by value ("h01", "h1"): byte order decides, so the order is total.
bool natural_less(const std::string& a, const std::string& b) {
  const int c = natural_compare(a, b);
  return c != 0 ? c < 0 : a < b;
}

std::vector<fs::path> csv_files(const fs::path& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec)) throw InputError(folder.string(), 0, "", "no such folder");
  if (!fs::is_directory(folder, ec)) throw InputError(folder.string(), 0, "", "not a folder");
  std::vector<fs::path> files;
  try {
    for (const auto& entry : fs::directory_iterator(folder)) {
      const std::string name = entry.path().filename().string();
      // Hidden files are skipped: copies to a USB stick leave "._h1.csv" beside "h1.csv".
      if (name.empty() || name.front() == '.') continue;
      if (lower(entry.path().extension().string()) != ".csv" || !entry.is_regular_file()) continue;
      files.push_back(entry.path());
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(folder.string(), 0, "", std::string("cannot list the folder: ") + e.code().message());
  }
  if (files.empty()) throw InputError(folder.string(), 0, "", "no .csv files in the folder");
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return files;
}

}  // namespace

int TimeHistory::rods() const { return static_cast<int>(force.cols()); }

int TimeHistory::samples() const { return static_cast<int>(t.size()); }

rig::VirtualHistory to_record(const TimeHistory& h) {
  rig::VirtualHistory r;
  r.t = h.t;
  r.force = h.force;
  r.alpha = h.alpha;
  r.beta = h.beta;
  return r;
}

TimeHistory to_time_history(const rig::VirtualHistory& r) {
  TimeHistory h;
  h.t = r.t;
  h.force = r.force;
  h.alpha = r.alpha;
  h.beta = r.beta;
  return h;
}

std::string TimeHistory::comment(const std::string& key) const {
  for (const auto& [k, v] : comments)
    if (k == key) return v;
  return "";
}

TimeHistory read_time_history(const fs::path& file, int expected_rods) {
  return read_file(file, {expected_rods, ""});
}

TimeHistory parse_time_history(std::istream& in, const std::string& file_name, int expected_rods) {
  return parse_text(read_all(in, file_name), file_name, {expected_rods, ""});
}

std::string format_time_history(const TimeHistory& h) {
  check_sizes(h);
  check_values(h);
  check_comments(h);
  const Eigen::Index n = h.force.cols();
  std::string out;
  out.reserve(static_cast<size_t>(h.t.size() * (3 * n + 1) * 24 + 256));
  // "# key:" for an empty value: no trailing blank.
  for (const auto& [key, value] : h.comments)
    out.append("# ").append(key).append(value.empty() ? ":" : ": ").append(value).append("\n");
  out.append("t");
  for (Eigen::Index k = 1; k <= n; ++k) out.append(",F").append(std::to_string(k));
  for (Eigen::Index k = 1; k <= n; ++k)
    out.append(",alpha").append(std::to_string(k)).append(",beta").append(std::to_string(k));
  out.append("\n");
  for (Eigen::Index i = 0; i < h.t.size(); ++i) {
    append_number(out, h.t(i));
    for (Eigen::Index k = 0; k < n; ++k) append_number(out.append(","), h.force(i, k));
    for (Eigen::Index k = 0; k < n; ++k) {
      append_number(out.append(","), h.alpha(i, k));
      append_number(out.append(","), h.beta(i, k));
    }
    out.append("\n");
  }
  return out;
}

void write_time_history(const fs::path& file, const TimeHistory& h) {
  // Formatted (and so checked) before anything touches the disk.
  write_text_atomically(file, format_time_history(h));
}

MeasurementSet read_measurement_set(const fs::path& folder, int expected_rods) {
  MeasurementSet set;
  set.files = csv_files(folder);
  for (const auto& file : set.files) {
    // Every file must have the rods of the first, when the caller did not say how many.
    RodRule rule{expected_rods, ""};
    if (expected_rods == 0 && !set.histories.empty())
      rule = {set.histories.front().rods(), ", as in " + set.files.front().filename().string()};
    set.histories.push_back(read_file(file, rule));
  }
  return set;
}

namespace {

bool holds_csv(const fs::path& folder) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name.front() != '.' && lower(entry.path().extension().string()) == ".csv" &&
        entry.is_regular_file())
      return true;
  }
  return false;
}

std::vector<fs::path> set_folders(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name.front() != '.' && entry.is_directory() && holds_csv(entry.path()))
      out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return out;
}

}  // namespace

MeasurementSets read_measurement_sets(const std::vector<fs::path>& paths, int expected_rods) {
  MeasurementSets out;
  MeasurementSet loose;
  for (const auto& path : paths) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path.string(), 0, "", "no such file or folder");
    if (!fs::is_directory(path, ec)) {
      loose.files.push_back(path);
      loose.histories.push_back(read_time_history(path, expected_rods));
      continue;
    }
    if (holds_csv(path)) {
      out.names.push_back(path.string());
      out.sets.push_back(read_measurement_set(path, expected_rods));
      continue;
    }
    const auto folders = set_folders(path);
    if (folders.empty()) throw InputError(path.string(), 0, "", "no .csv files in the folder or its subfolders");
    for (const auto& f : folders) {
      out.names.push_back(f.string());
      out.sets.push_back(read_measurement_set(f, expected_rods));
    }
  }
  if (!loose.files.empty()) {
    out.names.push_back("files");
    out.sets.push_back(std::move(loose));
  }
  return out;
}

}  // namespace rigflex::io
