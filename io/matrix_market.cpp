#include "io/matrix_market.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {
namespace {

// Far beyond any reduced model, and small enough that a corrupted size line
// of a coordinate file cannot make the reader allocate terabytes.
constexpr long long kMaxDenseEntries = 100'000'000;
// Either dimension alone: an empty matrix of 0 x 1e9 allocates nothing but
// was walked column by column for 47 s (found by fuzzing).
constexpr long long kMaxDimension = 1'000'000;

std::string format_double(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17);
  return std::string(buf, r.ptr);
}

std::string entry_name(Eigen::Index i, Eigen::Index j) {
  return "entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ")";
}

bool matrix_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::vector<std::string_view> matrix_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::vector<std::string_view> matrix_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && matrix_blank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !matrix_blank(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::string matrix_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool matrix_skippable(std::string_view line) {
  const auto t = matrix_tokens(line);
  return t.empty() || t.front().front() == '%';
}

enum class Storage { general, symmetric, skew_symmetric };

class Parser {
 public:
  Parser(std::string_view text, const std::string& source) : lines_(matrix_lines(text)), source_(source) {}

  Eigen::MatrixXd parse(const std::optional<MatrixShape>& expected) {
    read_header();
    read_size(expected);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows_, cols_);
    if (coordinate_) read_coordinates(A);
    else read_array(A);
    return A;
  }

 private:
  [[noreturn]] void fail(size_t line_index, const std::string& message) const {
    throw InputError(source_, static_cast<int>(line_index + 1), "", message);
  }

  void read_header() {
    static const char* kExpected =
        "expected the header '%%MatrixMarket matrix array|coordinate real|integer "
        "general|symmetric|skew-symmetric'";
    if (lines_.empty()) fail(0, std::string("empty file; ") + kExpected);
    const auto t = matrix_tokens(lines_[0]);
    if (t.empty() || matrix_lower(t[0]) != "%%matrixmarket") fail(0, kExpected);
    if (t.size() != 5) fail(0, "the header has " + std::to_string(t.size()) + " words; " + kExpected);
    if (matrix_lower(t[1]) != "matrix") fail(0, "object '" + std::string(t[1]) + "': only 'matrix' is read");
    const std::string format = matrix_lower(t[2]);
    if (format == "coordinate") coordinate_ = true;
    else if (format != "array") fail(0, "format '" + std::string(t[2]) + "': expected array or coordinate");
    const std::string field = matrix_lower(t[3]);
    if (field == "integer") integer_ = true;
    else if (field == "complex" || field == "pattern")
      fail(0, "field '" + std::string(t[3]) + "': only real and integer matrices are read");
    else if (field != "real") fail(0, "field '" + std::string(t[3]) + "': expected real or integer");
    const std::string symmetry = matrix_lower(t[4]);
    if (symmetry == "symmetric") storage_ = Storage::symmetric;
    else if (symmetry == "skew-symmetric") storage_ = Storage::skew_symmetric;
    else if (symmetry == "hermitian") fail(0, "symmetry 'hermitian' belongs to complex matrices, which are not read");
    else if (symmetry != "general")
      fail(0, "symmetry '" + std::string(t[4]) + "': expected general, symmetric or skew-symmetric");
  }

  long long count(std::string_view token, size_t line, const std::string& what) const {
    long long v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec != std::errc() || r.ptr != token.data() + token.size() || v < 0)
      fail(line, what + " '" + std::string(token) + "' is not a non-negative integer");
    return v;
  }

  void read_size(const std::optional<MatrixShape>& expected) {
    next_ = 1;
    while (next_ < lines_.size() && matrix_skippable(lines_[next_])) ++next_;
    if (next_ == lines_.size()) fail(lines_.size() - 1, "no size line after the header");
    size_line_ = next_++;
    const auto t = matrix_tokens(lines_[size_line_]);
    const size_t words = coordinate_ ? 3 : 2;
    if (t.size() != words)
      fail(size_line_, coordinate_ ? "expected the size line 'rows columns entries'" : "expected the size line 'rows columns'");
    const long long rows = count(t[0], size_line_, "row count");
    const long long cols = count(t[1], size_line_, "column count");
    if (storage_ != Storage::general && rows != cols)
      fail(size_line_, "a symmetric or skew-symmetric matrix must be square, not " + std::to_string(rows) + " x " +
                           std::to_string(cols));
    if (expected && (rows != expected->rows || cols != expected->cols))
      fail(size_line_, "the matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + " but " +
                           std::to_string(expected->rows) + " x " + std::to_string(expected->cols) +
                           " is expected" + (expected->origin.empty() ? "" : " (" + expected->origin + ")"));
    if (rows > kMaxDimension || cols > kMaxDimension)
      fail(size_line_, std::to_string(rows) + " x " + std::to_string(cols) + ": more than " +
                           std::to_string(kMaxDimension) + " rows or columns, beyond any reduced model");
    if (cols != 0 && rows > kMaxDenseEntries / cols)
      fail(size_line_, std::to_string(rows) + " x " + std::to_string(cols) + " is too large for a dense matrix");
    rows_ = static_cast<Eigen::Index>(rows);
    cols_ = static_cast<Eigen::Index>(cols);
    if (coordinate_) entries_ = count(t[2], size_line_, "entry count");
  }

  double value(std::string_view token, size_t line) const {
    // Some writers spell positive numbers with '+'; from_chars does not take it.
    std::string_view digits = token;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
    const char* end = digits.data() + digits.size();
    if (integer_) {
      long long v = 0;
      const auto r = std::from_chars(digits.data(), end, v);
      if (r.ec != std::errc() || r.ptr != end)
        fail(line, "value '" + std::string(token) + "' is not an integer (the header says integer)");
      return static_cast<double>(v);
    }
    double v = 0.0;
    const auto r = std::from_chars(digits.data(), end, v);
    if (r.ec == std::errc::result_out_of_range && r.ptr == end)
      fail(line, "value '" + std::string(token) + "' is outside the range of a double");
    if (r.ec != std::errc() || r.ptr != end) fail(line, "value '" + std::string(token) + "' is not a number");
    if (!std::isfinite(v)) fail(line, "value '" + std::string(token) + "' is not finite");
    return v;
  }

  void store(Eigen::MatrixXd& A, Eigen::Index i, Eigen::Index j, double v) const {
    A(i, j) = v;
    if (storage_ == Storage::symmetric) A(j, i) = v;
    if (storage_ == Storage::skew_symmetric) A(j, i) = -v;
  }

  Eigen::Index first_stored_row(Eigen::Index j) const {
    return storage_ == Storage::general ? 0 : storage_ == Storage::symmetric ? j : j + 1;
  }

  const char* storage_name() const {
    return storage_ == Storage::general ? "general" : storage_ == Storage::symmetric ? "symmetric" : "skew-symmetric";
  }

  void read_array(Eigen::MatrixXd& A) {
    const long long n = rows_;
    const long long total = storage_ == Storage::general          ? n * cols_
                            : storage_ == Storage::symmetric       ? n * (n + 1) / 2
                                                                   : n * (n - 1) / 2;
    // The position of the next stored value: column by column, and for the
    // symmetric storages only on and below (or strictly below) the diagonal.
    Eigen::Index i = 0, j = 0;
    auto settle = [&] {
      while (j < cols_ && i >= rows_) {
        ++j;
        i = first_stored_row(j);
      }
    };
    i = first_stored_row(0);
    settle();
    long long read = 0;
    for (; next_ < lines_.size(); ++next_) {
      if (matrix_skippable(lines_[next_])) continue;
      for (const auto token : matrix_tokens(lines_[next_])) {
        if (read == total)
          fail(next_, "more values than the " + std::to_string(total) + " of a " + std::to_string(rows_) + " x " +
                          std::to_string(cols_) + " " + storage_name() + " array (size on line " +
                          std::to_string(size_line_ + 1) + ")");
        store(A, i, j, value(token, next_));
        ++read;
        ++i;
        settle();
      }
    }
    if (read < total)
      fail(lines_.size() - 1, "only " + std::to_string(read) + " of the " + std::to_string(total) +
                                  " values of a " + std::to_string(rows_) + " x " + std::to_string(cols_) + " " +
                                  storage_name() + " array");
  }

  void read_coordinates(Eigen::MatrixXd& A) {
    std::vector<bool> seen(static_cast<size_t>(rows_ * cols_), false);
    long long read = 0;
    for (; next_ < lines_.size(); ++next_) {
      if (matrix_skippable(lines_[next_])) continue;
      const auto t = matrix_tokens(lines_[next_]);
      if (t.size() != 3) fail(next_, "expected an entry 'row column value', found " + std::to_string(t.size()) + " words");
      if (read == entries_)
        fail(next_, "more entries than the " + std::to_string(entries_) + " on the size line (line " +
                        std::to_string(size_line_ + 1) + ")");
      const long long r = count(t[0], next_, "row");
      const long long c = count(t[1], next_, "column");
      if (r < 1 || r > rows_ || c < 1 || c > cols_)
        fail(next_, "entry (" + std::to_string(r) + ", " + std::to_string(c) + ") is outside the " +
                        std::to_string(rows_) + " x " + std::to_string(cols_) + " matrix (indices start at 1)");
      const Eigen::Index i = static_cast<Eigen::Index>(r - 1), j = static_cast<Eigen::Index>(c - 1);
      if (i < first_stored_row(j))
        fail(next_, entry_name(i, j) + " lies above " + (storage_ == Storage::symmetric ? "" : "or on ") +
                        "the diagonal; a " + storage_name() + " file stores the lower triangle only");
      const auto k = static_cast<size_t>(j * rows_ + i);
      if (seen[k]) fail(next_, entry_name(i, j) + " is given twice");
      seen[k] = true;
      store(A, i, j, value(t[2], next_));
      ++read;
    }
    if (read < entries_)
      fail(lines_.size() - 1, "only " + std::to_string(read) + " of the " + std::to_string(entries_) +
                                  " entries announced on the size line (line " + std::to_string(size_line_ + 1) + ")");
  }

  std::vector<std::string_view> lines_;
  const std::string& source_;
  bool coordinate_ = false;
  bool integer_ = false;
  Storage storage_ = Storage::general;
  size_t next_ = 0;  // the next line to read
  size_t size_line_ = 0;
  Eigen::Index rows_ = 0, cols_ = 0;
  long long entries_ = 0;
};

}  // namespace

std::string matrix_market_text(const Eigen::MatrixXd& A, const std::string& comment) {
  std::string out = "%%MatrixMarket matrix array real general\n";
  for (auto line : matrix_lines(comment)) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.append("% ").append(line).append("\n");
  }
  out.append(std::to_string(A.rows())).append(" ").append(std::to_string(A.cols())).append("\n");
  out.reserve(out.size() + static_cast<size_t>(A.size()) * 25);
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      const double v = A(i, j);
      if (!std::isfinite(v))
        throw std::invalid_argument(entry_name(i, j) + " is " + format_double(v) +
                                    ": Matrix Market has no agreed spelling for NaN or infinities");
      out.append(format_double(v)).append("\n");
    }
  }
  return out;
}

void write_matrix_market(const std::filesystem::path& file, const Eigen::MatrixXd& A, const std::string& comment) {
  std::string text;
  try {
    text = matrix_market_text(A, comment);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file.string() + ": " + e.what());
  }
  write_text_atomically(file, text);
}

Eigen::MatrixXd parse_matrix_market(const std::string& text, const std::string& source,
                                    const std::optional<MatrixShape>& expected) {
  return Parser(text, source).parse(expected);
}

Eigen::MatrixXd read_matrix_market(const std::filesystem::path& file, const std::optional<MatrixShape>& expected) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file.string(), 0, "", "cannot read the file");
  return parse_matrix_market(text, file.string(), expected);
}

}  // namespace rigflex::io
