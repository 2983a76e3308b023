#pragma once
// The text of a measurement file as the reader, the writer and the set
// reader of io/measurement_csv.hpp all see it: lines, comma separated
// fields, numbers that read back exactly, and the column names of the data
// contract (shared/spec/rig-conventions.md). Not part of the API.
#include <string>
#include <string_view>
#include <vector>

namespace rigflex::io::measurement_text {

inline bool blank(char c) { return c == ' ' || c == '\t'; }

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

inline bool is_blank_line(std::string_view s) { return trim(s).empty(); }

// Lines without their terminator; "\r\n" and "\n" both end a line (loggers on
// Windows write the former).
std::vector<std::string_view> split_lines(std::string_view text);

// Comma separated, blanks around each field trimmed. No quoting: the contract
// has none, and neither numbers nor column names need it.
// Into `fields` (cleared first), so that a reader splitting thousands of rows reuses one vector.
void split_fields(std::string_view line, std::vector<std::string_view>& fields);
std::vector<std::string_view> split_fields(std::string_view line);

// A field as shown in a message; long garbage is cut so the message stays readable.
std::string quoted(std::string_view s);
std::string lower(std::string_view s);
bool valid_utf8(std::string_view s);

// The shortest decimal that reads back as the same double (to_chars without a
// precision), so files are exact, as short as can be and deterministic.
void append_number(std::string& out, double v);
std::string number_text(double v);

enum class Quantity { time, force, alpha, beta, other };

struct Column {
  Quantity quantity = Quantity::other;
  int rod = 0;  // 1-based, for force, alpha and beta
};

// Exact names only: "t", "F<k>", "alpha<k>", "beta<k>" with k written without
// leading zeros. Anything else ("T", "F01", "time") is an unknown column,
// which the contract says readers ignore.
Column classify(std::string_view name);
std::string column_name(Quantity q, int rod);

}  // namespace rigflex::io::measurement_text
