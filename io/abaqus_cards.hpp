#pragma once
// The cards of an Abaqus / CalculiX input deck: each keyword line with its
// parameters and the data lines that follow it, *INCLUDE files read in
// place, comments (**) and blank lines dropped. Keywords, parameter names
// and parameter values are case-insensitive in the format: keywords and
// parameter names are stored in upper case, values as written.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rigflex::io {

struct DeckWhere {
  std::string file;
  int line = 0;
};

struct DeckDataLine {
  DeckWhere at;
  std::vector<std::string> fields;  // split at commas, trimmed; a trailing comma adds no field
  std::string text;                 // the line as written, trimmed
};

struct DeckCard {
  std::string keyword;  // upper case, single spaces: "BEAM SECTION"
  DeckWhere at;
  std::map<std::string, std::string> params;  // upper-case name -> value as written ("" for a flag)
  std::vector<DeckDataLine> data;

  bool has(const std::string& name) const { return params.count(name) != 0; }
};

// Throws InputError naming the file and line: a data line before the first
// keyword, a parameter without a name, an *INCLUDE without INPUT=, of a
// file that is not there or not a regular file, or nested deeper than 16
// (an include cycle).
std::vector<DeckCard> read_deck_cards(const std::string& text, const std::string& source);

// Upper case, for the format's case-insensitive names.
std::string deck_upper(std::string s);

}  // namespace rigflex::io
