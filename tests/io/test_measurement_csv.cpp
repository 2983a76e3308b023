// Measurement files (time histories of the rig, CSV): what the data contract
// allows reads, every number written reads back bit for bit, and bad input
// names the file, the line and the column; nothing is written half-way.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

#include "support/awkward_doubles.hpp"
#include "support/input_errors.hpp"
#include "support/temp_files.hpp"
#include "io/input_error.hpp"
#include "io/measurement_csv.hpp"

namespace rigflex {
namespace {

namespace fs = std::filesystem;
using rig::Record;

using test::read_text;
using test::write_text;

std::set<std::string> file_names(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

Record parse(const std::string& text, int expected_rods = 0) {
  std::istringstream in(text);
  return io::parse_record_csv(in, "h1.csv", expected_rods);
}

// The error of parsing `text`; fails the test if there is none.
io::InputError csv_error_of(const std::string& text, int expected_rods = 0) {
  return test::input_error_of([&] { parse(text, expected_rods); }, "the text:\n" + text);
}

void expect_error(const io::InputError& e, int line, const std::string& key, const std::string& words) {
  EXPECT_EQ(e.file(), "h1.csv") << e.what();
  EXPECT_EQ(e.line(), line) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
}

// A file as a table of fields, so a test can change one field or column and
// know its line: comment lines first, the header on line comments + 1, row r
// (0-based) on line comments + 2 + r.
struct Table {
  std::vector<std::string> comments;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  int header_line() const { return static_cast<int>(comments.size()) + 1; }
  int row_line(int r) const { return header_line() + 1 + r; }
  size_t column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<size_t>(it - header.begin());
  }
  std::string& at(int r, const std::string& name) { return rows[static_cast<size_t>(r)][column(name)]; }
  void remove_column(const std::string& name) {
    const size_t c = column(name);
    header.erase(header.begin() + static_cast<std::ptrdiff_t>(c));
    for (auto& row : rows) row.erase(row.begin() + static_cast<std::ptrdiff_t>(c));
  }
  void add_column(const std::string& name, const std::string& value) {
    header.push_back(name);
    for (auto& row : rows) row.push_back(value);
  }
  std::string text(const std::string& eol = "\n") const {
    std::string s;
    for (const auto& c : comments) s += c + eol;
    auto line = [&](const std::vector<std::string>& fields) {
      for (size_t i = 0; i < fields.size(); ++i) s += (i ? "," : "") + fields[i];
      s += eol;
    };
    line(header);
    for (const auto& row : rows) line(row);
    return s;
  }
};

// `rods` rods, `rows` samples at 500 Hz, each value distinct and exact in decimal.
Table sample_table(int rods, int rows) {
  Table t;
  t.comments = {"# sample_rate_hz: 500", "# body: light-truck"};
  t.header = {"t"};
  for (int k = 1; k <= rods; ++k) t.header.push_back("F" + std::to_string(k));
  for (int k = 1; k <= rods; ++k) {
    t.header.push_back("alpha" + std::to_string(k));
    t.header.push_back("beta" + std::to_string(k));
  }
  for (int r = 0; r < rows; ++r) {
    std::vector<std::string> row = {std::to_string(2 * r) + "e-3"};
    for (int k = 1; k <= rods; ++k) row.push_back(std::to_string(1000 * k + r) + ".25");
    for (int k = 1; k <= rods; ++k) {
      row.push_back("0.0" + std::to_string(k) + std::to_string(r));
      row.push_back("-0.0" + std::to_string(k) + std::to_string(r) + "5");
    }
    t.rows.push_back(row);
  }
  return t;
}

// Awkward values everywhere except time, which must increase: awkward steps.
// Awkward mantissas (denormals, signed zeros, every digit count) kept below
// 2^max_exponent: the reader refuses what no rig measures (|F| > 1e8 N,
// |angle| > pi/2), so the round trip is over the values it accepts.
Eigen::MatrixXd below(Eigen::MatrixXd x, int max_exponent) {
  for (double& v : x.reshaped()) {
    int e = 0;
    const double m = std::frexp(v, &e);
    if (e > max_exponent) v = std::ldexp(m, max_exponent);
  }
  return x;
}

Record awkward_history(int rods, int samples) {
  test::AwkwardDoubles a;
  Record h;
  h.provenance.comments = {{"sample_rate_hz", "500"}, {"body", "light-truck"}, {"note", "a: b, c"}, {"empty", ""}};
  h.t.resize(samples);
  h.t(0) = -std::numeric_limits<double>::denorm_min();
  for (int i = 1; i < samples; ++i)
    h.t(i) = std::nextafter(h.t(i - 1) + std::abs(a.next()) * 1e-3, std::numeric_limits<double>::infinity());
  h.t(1) = -0.0;  // between -denorm_min and the rest: -0 itself must come back
  h.force = below(a.matrix(samples, rods), 26);  // |F| < 6.7e7 N
  h.alpha = below(a.matrix(samples, rods), 0);   // |angle| < 1 rad
  h.beta = below(a.matrix(samples, rods), 0);
  h.force(0, 0) = -0.0;
  h.force(3, 0) = -1e8;  // the limits themselves are accepted
  h.alpha(1, 0) = std::numeric_limits<double>::denorm_min();
  h.beta(2, 0) = 1.5707963267948966;
  return h;
}

void expect_bits_equal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      EXPECT_EQ(a(i, j), b(i, j)) << what << "(" << i << ", " << j << ")";
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a(i, j)), std::bit_cast<std::uint64_t>(b(i, j)))
          << what << "(" << i << ", " << j << ")";
    }
}

void expect_same(const Record& a, const Record& b) {
  EXPECT_EQ(a.provenance.comments, b.provenance.comments);
  expect_bits_equal(a.t, b.t, "t");
  expect_bits_equal(a.force, b.force, "force");
  expect_bits_equal(a.alpha, b.alpha, "alpha");
  expect_bits_equal(a.beta, b.beta, "beta");
}

// ---------------------------------------------------------------- writing and reading back

TEST(TimeHistoryCsv, RoundTripIsBitExact) {
  test::TempDir dir("rigflex-measurement");
  for (const int rods : {4, 3}) {
    const Record h = awkward_history(rods, 40);
    const fs::path file = dir.path() / ("h" + std::to_string(rods) + ".csv");
    io::write_record_csv(file, h);
    const Record back = io::read_record_csv(file);
    EXPECT_EQ(back.rods(), rods);
    EXPECT_EQ(back.samples(), 40);
    expect_same(h, back);
    EXPECT_EQ(io::read_record_csv(file, rods).samples(), 40);
    // Deterministic: the file is the formatted text, the same every time.
    EXPECT_EQ(read_text(file), io::format_record_csv(h));
    EXPECT_EQ(io::format_record_csv(back), io::format_record_csv(h));
  }
  EXPECT_EQ(file_names(dir.path()), (std::set<std::string>{"h3.csv", "h4.csv"}));  // no temporary left
}

TEST(TimeHistoryCsv, FormatIsTheContractsLayoutWithShortestNumbers) {
  Record h;
  h.provenance.comments = {{"sample_rate_hz", "500"}, {"empty", ""}};
  h.t = Eigen::Vector2d(0.0, 0.002);
  h.force = Eigen::MatrixXd{{1500.25, 1e22, -0.0}, {0.1, 1.0 / 3, 5e-324}};
  h.alpha = Eigen::MatrixXd{{0.01, 0.02, 0.03}, {-0.01, -0.02, -0.03}};
  h.beta = Eigen::MatrixXd{{1, 2, 3}, {4, 5, 6}};
  EXPECT_EQ(io::format_record_csv(h),
            "# sample_rate_hz: 500\n"
            "# empty:\n"
            "t,F1,F2,F3,alpha1,beta1,alpha2,beta2,alpha3,beta3\n"
            "0,1500.25,1e+22,-0,0.01,1,0.02,2,0.03,3\n"
            "0.002,0.1,0.3333333333333333,5e-324,-0.01,4,-0.02,5,-0.03,6\n");
}

TEST(TimeHistoryCsv, ReadsTheSampleTable) {
  const Table table = sample_table(4, 3);
  const Record h = parse(table.text());
  EXPECT_EQ(h.rods(), 4);
  EXPECT_EQ(h.samples(), 3);
  EXPECT_EQ(h.t(2), 0.004);
  EXPECT_EQ(h.force(1, 2), 3001.25);
  EXPECT_EQ(h.alpha(2, 3), 0.042);
  EXPECT_EQ(h.beta(0, 1), -0.0205);
}

TEST(TimeHistoryCsv, ThreeAndFourRodsInferredOrExpected) {
  for (const int rods : {3, 4}) {
    const std::string text = sample_table(rods, 5).text();
    EXPECT_EQ(parse(text).rods(), rods);
    EXPECT_EQ(parse(text, rods).rods(), rods);
    EXPECT_EQ(parse(text, rods).force.rows(), 5);
  }
}

TEST(TimeHistoryCsv, ColumnsInAnyOrderAndUnknownColumnsIgnored) {
  const Table table = sample_table(4, 6);
  const Record reference = parse(table.text());
  Table shuffled = table;
  shuffled.add_column("temperature", "warm");  // not a number: never read
  shuffled.add_column("F01", "x");             // not a contract name either
  std::vector<size_t> order(shuffled.header.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  Table permuted = shuffled;
  for (size_t c = 0; c < order.size(); ++c) {
    permuted.header[c] = shuffled.header[order[c]];
    for (size_t r = 0; r < shuffled.rows.size(); ++r) permuted.rows[r][c] = shuffled.rows[r][order[c]];
  }
  ASSERT_NE(permuted.header, shuffled.header);
  expect_same(parse(permuted.text()), reference);
}

TEST(TimeHistoryCsv, CommentsParsed) {
  Table table = sample_table(3, 2);
  table.comments = {"# sample_rate_hz: 500",
                    "",
                    "#body:light-truck",
                    "# a free remark without a colon",
                    "#   operator  :  J. Doe  ",
                    "# url: http://rig:8080/log",
                    "# : no key",
                    "# sample_rate_hz: 1000",
                    "# Größe: ü"};
  const Record h = parse(table.text());
  const std::vector<std::pair<std::string, std::string>> expected = {{"sample_rate_hz", "500"},
                                                                     {"body", "light-truck"},
                                                                     {"operator", "J. Doe"},
                                                                     {"url", "http://rig:8080/log"},
                                                                     {"sample_rate_hz", "1000"},
                                                                     {"Größe", "ü"}};
  EXPECT_EQ(h.provenance.comments, expected);
  EXPECT_EQ(h.comment("sample_rate_hz"), "500");  // the first of repeated keys
  EXPECT_EQ(h.comment("body"), "light-truck");
  EXPECT_EQ(h.comment("absent"), "");
  EXPECT_EQ(h.samples(), 2);
}

TEST(TimeHistoryCsv, WindowsLineEndingsBomBlanksAndTrailingBlankLines) {
  const Table table = sample_table(4, 4);
  const Record reference = parse(table.text());
  Table spaced = table;
  spaced.at(1, "F2") = "+" + spaced.at(1, "F2");  // some loggers write a '+'
  for (auto& f : spaced.header) f = " " + f + "\t";
  for (auto& row : spaced.rows)
    for (auto& f : row) f = "  " + f + " ";
  const std::string text = "\xEF\xBB\xBF" + spaced.text("\r\n") + "\r\n  \r\n\n";
  expect_same(parse(text), reference);
  EXPECT_EQ(parse("\xEF\xBB\xBF" + table.text()).provenance.comments, reference.provenance.comments);
}

// ---------------------------------------------------------------- errors: file, line, column

TEST(TimeHistoryCsvErrors, MissingColumn) {
  for (const std::string name : {"t", "F2", "alpha1", "beta3"}) {
    Table table = sample_table(3, 3);
    table.remove_column(name);
    expect_error(csv_error_of(table.text()), table.header_line(), name, "missing column");
  }
  // F1..Fn must be contiguous: F3 missing while F4 is there.
  Table gap = sample_table(4, 3);
  gap.remove_column("F3");
  expect_error(csv_error_of(gap.text()), gap.header_line(), "F3", "missing column");
  // Names are exact, and the message says why "T" is not "t".
  Table upper = sample_table(3, 3);
  upper.header[upper.column("t")] = "T";
  expect_error(csv_error_of(upper.text()), upper.header_line(), "t", "case-sensitive");
  // A semicolon separated file has one header field.
  std::string semicolons = sample_table(3, 2).text();
  std::replace(semicolons.begin(), semicolons.end(), ',', ';');
  expect_error(csv_error_of(semicolons), 3, "t", "comma separated");
}

TEST(TimeHistoryCsvErrors, DuplicatedColumn) {
  for (const std::string name : {"t", "F1", "alpha2", "beta3"}) {
    Table table = sample_table(3, 3);
    table.add_column(name, "0");
    expect_error(csv_error_of(table.text()), table.header_line(), name, "duplicated column");
  }
  Table unknown = sample_table(3, 3);  // unknown columns may repeat: nobody reads them
  unknown.add_column("note", "a");
  unknown.add_column("note", "b");
  EXPECT_EQ(parse(unknown.text()).rods(), 3);
}

TEST(TimeHistoryCsvErrors, NonNumericOrNonFiniteValue) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"abc", "not a number"},  {"nan", "not finite"},      {"NaN", "not finite"},          {"inf", "not finite"},
      {"-inf", "not finite"},   {"infinity", "not finite"}, {"1e400", "outside the range"}, {"", "empty value"},
      {"1.5x", "not a number"}, {"0x10", "not a number"},   {"1 5", "not a number"},        {"++1", "not a number"}};
  for (const auto& [value, words] : bad)
    for (const std::string column : {"t", "F2", "alpha3", "beta1"}) {
      Table table = sample_table(3, 4);
      table.at(2, column) = value;
      SCOPED_TRACE(column + " = '" + value + "'");
      expect_error(csv_error_of(table.text()), table.row_line(2), column, words);
    }
}

TEST(TimeHistoryCsvErrors, WrongFieldCount) {
  Table few = sample_table(4, 4);
  few.rows[1].pop_back();
  expect_error(csv_error_of(few.text()), few.row_line(1), "beta4", "fields but the header has");
  Table many = sample_table(4, 4);
  many.rows[3].push_back("1");
  expect_error(csv_error_of(many.text()), many.row_line(3), "", "decimal point");
  Table comma = sample_table(3, 4);
  comma.at(0, "F1") = "1000,25";  // decimal comma
  expect_error(csv_error_of(comma.text()), comma.row_line(0), "", "decimal point");
  // A blank line among the samples is not a trailing blank line.
  Table blank = sample_table(3, 4);
  blank.rows.insert(blank.rows.begin() + 2, std::vector<std::string>{""});
  expect_error(csv_error_of(blank.text()), blank.row_line(2), "", "blank line");
}

TEST(TimeHistoryCsvErrors, TimeNotStrictlyIncreasing) {
  Table equal = sample_table(3, 5);
  equal.at(3, "t") = equal.at(2, "t");
  expect_error(csv_error_of(equal.text()), equal.row_line(3), "t", "strictly increase");
  Table back = sample_table(3, 5);
  back.at(4, "t") = "0.001";
  expect_error(csv_error_of(back.text()), back.row_line(4), "t", "not after");
}

TEST(TimeHistoryCsvErrors, RodCountDifferentFromExpected) {
  const Table three = sample_table(3, 3);
  expect_error(csv_error_of(three.text(), 4), three.header_line(), "F4", "3 rods");
  const Table four = sample_table(4, 3);
  expect_error(csv_error_of(four.text(), 3), four.header_line(), "F4", "4 rods");
  // Angles of a rod without a force column.
  Table extra = sample_table(4, 3);
  extra.add_column("alpha5", "0");
  extra.add_column("beta5", "0");
  expect_error(csv_error_of(extra.text()), extra.header_line(), "alpha5", "no rod 5");
  Table beta = sample_table(3, 3);
  beta.add_column("beta4", "0");
  expect_error(csv_error_of(beta.text()), beta.header_line(), "beta4", "no rod 4");
  EXPECT_THROW(parse(three.text(), -1), std::invalid_argument);
}

TEST(TimeHistoryCsvErrors, NoDataRows) {
  Table header_only = sample_table(3, 0);
  expect_error(csv_error_of(header_only.text()), header_only.header_line(), "", "no data rows");
  expect_error(csv_error_of(header_only.text() + "\n \r\n"), header_only.header_line(), "", "no data rows");
  expect_error(csv_error_of(""), 1, "", "empty");
  expect_error(csv_error_of("# body: light-truck\n# sample_rate_hz: 500\n"), 2, "", "no header line");
}

TEST(TimeHistoryCsvErrors, CommentNotUtf8) {
  Table table = sample_table(3, 2);
  table.comments[1] = "# operator: M\xFCller";  // Latin-1
  expect_error(csv_error_of(table.text()), 2, "", "UTF-8");
}

TEST(TimeHistoryCsvErrors, FileNamedInErrors) {
  test::TempDir dir("rigflex-measurement");
  const fs::path file = dir.path() / "run 7.csv";
  Table table = sample_table(3, 3);
  table.at(1, "alpha2") = "n/a";
  write_text(file, table.text());
  try {
    io::read_record_csv(file);
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(e.line(), table.row_line(1));
    EXPECT_EQ(e.key(), "alpha2");
    EXPECT_EQ(std::string(e.what()), file.string() + ":5: key 'alpha2': value 'n/a' is not a number");
  }
  try {
    io::read_record_csv(dir.path() / "absent.csv");
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

// ---------------------------------------------------------------- the writer refuses, and writes nothing

TEST(TimeHistoryCsvWrite, InvalidHistoryCreatesNoFile) {
  test::TempDir dir("rigflex-measurement");
  const fs::path file = dir.path() / "sub" / "h1.csv";
  const Record good = awkward_history(4, 5);
  const std::vector<std::pair<std::string, std::function<void(Record&)>>> breakages = {
      {"no samples", [](Record& h) { h = Record{}; }},
      {"alpha is 5 x 4, expected 5 x 3", [](Record& h) { h.force.conservativeResize(5, 3); }},
      {"alpha is 4 x 4", [](Record& h) { h.alpha.conservativeResize(4, 4); }},
      {"beta is 5 x 3", [](Record& h) { h.beta.conservativeResize(5, 3); }},
      {"F3 of sample 2 is nan", [](Record& h) { h.force(1, 2) = std::nan(""); }},
      {"alpha1 of sample 5 is inf", [](Record& h) { h.alpha(4, 0) = std::numeric_limits<double>::infinity(); }},
      {"beta4 of sample 1 is -inf", [](Record& h) { h.beta(0, 3) = -std::numeric_limits<double>::infinity(); }},
      {"t of sample 3 is nan", [](Record& h) { h.t(2) = std::nan(""); }},
      {"t of sample 4", [](Record& h) { h.t(3) = h.t(2); }},
      {"empty key", [](Record& h) { h.provenance.comments.push_back({"", "x"}); }},
      {"contains ':'", [](Record& h) { h.provenance.comments.push_back({"a:b", "x"}); }},
      {"line break", [](Record& h) { h.provenance.comments.push_back({"a", "x\ny"}); }},
      {"blanks", [](Record& h) { h.provenance.comments.push_back({"a", " x"}); }},
      {"UTF-8", [](Record& h) { h.provenance.comments.push_back({"a", "M\xFCller"}); }}};
  for (const auto& [words, breakage] : breakages) {
    Record h = good;
    breakage(h);
    try {
      io::write_record_csv(file, h);
      ADD_FAILURE() << "no error: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_THROW(io::format_record_csv(h), std::invalid_argument) << words;
    EXPECT_TRUE(file_names(dir.path()).empty()) << words;
  }
  // An earlier file stays as it was.
  io::write_record_csv(file, good);
  const std::string before = read_text(file);
  Record bad = good;
  bad.beta(2, 2) = std::nan("");
  EXPECT_THROW(io::write_record_csv(file, bad), std::invalid_argument);
  EXPECT_EQ(read_text(file), before);
  EXPECT_EQ(file_names(file.parent_path()), std::set<std::string>{"h1.csv"});
}

// ---------------------------------------------------------------- sets of time histories

TEST(MeasurementSet, NaturalOrderAndOnlyCsvFiles) {
  test::TempDir dir("rigflex-measurement");
  const std::vector<std::string> names = {"h10.csv", "h2.csv", "h1.csv", "h3.CSV", "h02b.csv", "h9.csv"};
  for (size_t i = 0; i < names.size(); ++i) {
    Table table = sample_table(4, 3 + static_cast<int>(i));
    write_text(dir.path() / names[i], table.text());
  }
  write_text(dir.path() / "notes.txt", "not a time history");
  write_text(dir.path() / "._h1.csv", "\x05\x16\x07 not a time history");  // macOS metadata beside h1.csv
  fs::create_directories(dir.path() / "old.csv");           // a folder, not a file
  const io::MeasurementSet set = io::read_measurement_set(dir.path());
  std::vector<std::string> order;
  for (const auto& f : set.files) order.push_back(f.filename().string());
  EXPECT_EQ(order, (std::vector<std::string>{"h1.csv", "h2.csv", "h02b.csv", "h3.CSV", "h9.csv", "h10.csv"}));
  ASSERT_EQ(set.records.size(), set.files.size());
  for (size_t i = 0; i < set.files.size(); ++i) {
    const auto at = std::find(names.begin(), names.end(), order[i]) - names.begin();
    EXPECT_EQ(set.records[i].samples(), 3 + at) << order[i];
    EXPECT_EQ(set.records[i].rods(), 4);
  }
  EXPECT_EQ(io::read_measurement_set(dir.path(), 4).files, set.files);
}

TEST(MeasurementSet, RodCountMismatch) {
  test::TempDir dir("rigflex-measurement");
  write_text(dir.path() / "h1.csv", sample_table(4, 3).text());
  write_text(dir.path() / "h2.csv", sample_table(4, 3).text());
  const Table three = sample_table(3, 3);
  write_text(dir.path() / "h10.csv", three.text());
  try {
    io::read_measurement_set(dir.path());
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "h10.csv").string());
    EXPECT_EQ(e.line(), three.header_line());
    EXPECT_EQ(e.key(), "F4");
    EXPECT_NE(std::string(e.what()).find("as in h1.csv"), std::string::npos) << e.what();
  }
  // With the rig's rod count, the first file is checked too.
  try {
    io::read_measurement_set(dir.path(), 3);
    ADD_FAILURE() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), (dir.path() / "h1.csv").string());
    EXPECT_EQ(e.key(), "F4");
  }
}

TEST(MeasurementSet, EmptyOrMissingFolder) {
  test::TempDir dir("rigflex-measurement");
  write_text(dir.path() / "readme.txt", "");
  const std::vector<std::pair<fs::path, std::string>> cases = {{dir.path(), "no .csv or .csv.gz files"},
                                                               {dir.path() / "absent", "no such folder"},
                                                               {dir.path() / "readme.txt", "not a folder"}};
  for (const auto& [folder, words] : cases) {
    try {
      io::read_measurement_set(folder);
      ADD_FAILURE() << "no error: " << words;
    } catch (const io::InputError& e) {
      EXPECT_EQ(e.file(), folder.string());
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
}

// The record keeps where it came from: the file, the line of its first
// sample and the comments; a record error on sample k names line
// first_sample_line + k of that file.
TEST(RecordProvenance, FileLinesAndCommentsOfARecordRead) {
  Table table = sample_table(3, 4);
  table.comments = {"# sample_rate_hz: 500", "# remark without a key", "# body: light-truck"};
  const Record h = parse(table.text());
  EXPECT_EQ(h.provenance.file, "h1.csv");
  EXPECT_EQ(h.provenance.first_sample_line, table.row_line(0));
  EXPECT_EQ(h.provenance.line_of(2), table.row_line(2));
  EXPECT_EQ(h.provenance.line_of(-1), 0);
  EXPECT_EQ(h.comment("body"), "light-truck");
  EXPECT_EQ(h.sample_rate_hz, 500.0);

  const std::vector<Record> records = {Record{}, h};
  rig::RecordError e(3, "alpha2", "impossible angle");
  e.set_history(1);
  const io::InputError located = io::record_input_error(records, e);
  EXPECT_EQ(located.file(), "h1.csv");
  EXPECT_EQ(located.line(), table.row_line(3));
  EXPECT_EQ(located.key(), "alpha2");
  EXPECT_EQ(located.reason(), "impossible angle");
  // A whole-record error names the file without a line; a record not read
  // from a file, or an unknown history, names no file.
  rig::RecordError whole(-1, "", "wrong rods");
  whole.set_history(1);
  EXPECT_EQ(io::record_input_error(records, whole).line(), 0);
  EXPECT_EQ(io::record_input_error(records, whole).file(), "h1.csv");
  e.set_history(0);
  EXPECT_EQ(io::record_input_error(records, e).file(), "(a measurement)");
  e.set_history(7);
  EXPECT_EQ(io::record_input_error(records, e).file(), "(a measurement)");
}

// Without a sample_rate_hz comment the nominal rate comes from the time stamps.
TEST(RecordProvenance, SampleRateFromTheTimeStampsWithoutAComment) {
  Table table = sample_table(3, 5);
  table.comments.clear();
  const Record h = parse(table.text());
  EXPECT_TRUE(h.provenance.comments.empty());
  EXPECT_NEAR(h.sample_rate_hz, 500.0, 1e-9);
  Eigen::VectorXd one(1);
  one << 0.0;
  EXPECT_EQ(rig::nominal_sample_rate(one, {}), 0.0);
  EXPECT_NEAR(rig::nominal_sample_rate(h.t, {{"sample_rate_hz", "not a number"}}), 500.0, 1e-9);
}

}  // namespace
}  // namespace rigflex

namespace rigflex {
namespace {

// Three rods swinging for 3 s at 100 Hz; `hold(k, value)` may replace
// channel `column` (0: t, 1..3: F, then alpha/beta pairs) of sample k.
std::string swing_csv(const std::function<void(int, int, double&)>& hold) {
  std::ostringstream s;
  s << "t,F1,F2,F3,alpha1,beta1,alpha2,beta2,alpha3,beta3\n";
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.01 * k, w = 2 * M_PI * 0.5;
    double v[10] = {t,
                    600 + 2 * std::cos(2 * w * t),
                    610 + 2 * std::cos(2 * w * t + 1),
                    590 + std::sin(2 * w * t),
                    0.02 * std::sin(w * t),
                    0.01 * std::cos(w * t),
                    0.02 * std::sin(w * t + 1),
                    0.01 * std::cos(w * t + 1),
                    0.02 * std::sin(w * t + 2),
                    0.01 * std::cos(w * t + 2)};
    for (int c = 0; c < 10; ++c) hold(k, c, v[c]);
    for (int c = 0; c < 10; ++c) s << (c ? "," : "") << v[c];
    s << "\n";
  }
  return s.str();
}

TEST(TimeHistoryCsv, AChannelStuckForASecondIsReadWithAWarning) {
  const std::string text = swing_csv([](int k, int c, double& v) {
    if (c == 5 && k >= 100 && k <= 220) v = 0.0042;  // beta1 stuck mid-swing from t = 1.0 s to 2.2 s
  });
  std::istringstream in(text);
  const Record r = io::parse_record_csv(in, "stuck.csv");
  ASSERT_EQ(r.provenance.warnings.size(), 1u);
  EXPECT_EQ(r.provenance.warnings[0], "line 102: beta1 holds 0.0042 for 1.2 s (121 samples): a stuck sensor?");
}

TEST(TimeHistoryCsv, ALiveRecordHasNoWarning) {
  std::istringstream in(swing_csv([](int, int, double&) {}));
  EXPECT_TRUE(io::parse_record_csv(in, "live.csv").provenance.warnings.empty());
}

// A sample_rate_hz comment is checked against the time stamps (100 Hz
// here): within 1 % it agrees (a logger's nominal rate), beyond it is read
// with a warning; a comment that is no number is left to the stamps.
TEST(TimeHistoryCsv, ASampleRateCommentTheStampsContradictIsWarned) {
  const auto warnings = [](const std::string& comment) {
    std::istringstream in("# sample_rate_hz: " + comment + "\n" + swing_csv([](int, int, double&) {}));
    return io::parse_record_csv(in, "rate.csv").provenance.warnings;
  };
  EXPECT_TRUE(warnings("100").empty());
  EXPECT_TRUE(warnings("100.9").empty());
  const auto off = warnings("500");
  ASSERT_EQ(off.size(), 1u);
  EXPECT_EQ(off[0], "the comment gives sample_rate_hz: 500 but the time stamps (column t) 100 Hz; the stamps are used");
  EXPECT_EQ(warnings("101.1").size(), 1u);
  EXPECT_TRUE(warnings("fast").empty());
}

}  // namespace
}  // namespace rigflex
