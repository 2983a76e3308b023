#pragma once
// Edits of a valid input text into a bad one, and the line an error about it
// must name, for the tests of readers.
#include <gtest/gtest.h>

#include <string>

namespace rigflex::test {

// `s` with the first `from` replaced by `to` (a test failure if absent).
inline std::string replace_first(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

// 1-based line of the first occurrence of `needle` in `text`, found
// independently of the reader (0 and a test failure if absent).
inline int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  if (at == std::string::npos) return 0;
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += text[i] == '\n';
  return line;
}

}  // namespace rigflex::test
