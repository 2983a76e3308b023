#include "io/abaqus_cards.hpp"

#include <algorithm>
#include <cctype>

#include "io/file_text.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {
namespace fs = std::filesystem;

namespace {

constexpr int kMaxIncludeDepth = 16;

std::string trim_field(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(trim_field(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

std::string collapse_spaces(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == ' ' || c == '\t') {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

DeckCard keyword_card(const std::string& line, const DeckWhere& at) {
  const std::vector<std::string> parts = split_fields(line.substr(1));
  DeckCard card;
  card.at = at;
  card.keyword = deck_upper(collapse_spaces(parts.front()));
  if (card.keyword.empty()) throw InputError(at.file, at.line, "*", "a keyword line names no keyword");
  for (size_t i = 1; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (p.empty()) continue;
    const auto eq = p.find('=');
    const std::string name = deck_upper(collapse_spaces(trim_field(p.substr(0, eq))));
    if (name.empty()) throw InputError(at.file, at.line, "*" + card.keyword, "a parameter '" + p + "' without a name");
    card.params[name] = eq == std::string::npos ? "" : trim_field(p.substr(eq + 1));
  }
  return card;
}

void collect_cards(const std::string& text, const std::string& source, int depth, std::vector<DeckCard>& cards) {
  size_t pos = 0;
  int number = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string t = trim_field(line);
    if (t.empty() || t.rfind("**", 0) == 0) continue;
    const DeckWhere at{source, number};
    if (t.front() != '*') {
      if (cards.empty()) throw InputError(source, number, "", "a data line before the first keyword");
      cards.back().data.push_back({at, split_fields(t), t});
      continue;
    }
    DeckCard card = keyword_card(t, at);
    if (card.keyword != "INCLUDE") {
      cards.push_back(std::move(card));
      continue;
    }
    const auto input = card.params.find("INPUT");
    if (input == card.params.end() || input->second.empty())
      throw InputError(source, number, "*INCLUDE", "INPUT= names no file");
    if (depth >= kMaxIncludeDepth)
      throw InputError(source, number, "*INCLUDE",
                       "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " (a cycle?)");
    std::string name = input->second;
    if (name.size() >= 2 && (name.front() == '"' || name.front() == '\'') && name.back() == name.front())
      name = name.substr(1, name.size() - 2);
    fs::path file(name);
    if (file.is_relative()) file = fs::path(source).parent_path() / file;
    std::error_code ec;
    // Kernel and device files can block or never end.
    const std::string canonical = fs::weakly_canonical(file, ec).string();
    for (const char* system : {"/proc/", "/sys/", "/dev/"})
      if (canonical.rfind(system, 0) == 0)
        throw InputError(source, number, "*INCLUDE", "'" + file.string() + "' is a system file, not a deck");
    if (!fs::is_regular_file(file, ec))
      throw InputError(source, number, "*INCLUDE", "'" + file.string() + "' is not a file that can be read");
    collect_cards(read_file_text(file), file.string(), depth + 1, cards);
  }
}

}  // namespace

std::string deck_upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

std::vector<DeckCard> read_deck_cards(const std::string& text, const std::string& source) {
  std::vector<DeckCard> cards;
  collect_cards(text, source, 0, cards);
  return cards;
}

}  // namespace rigflex::io
