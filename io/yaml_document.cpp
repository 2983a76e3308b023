#include "io/yaml_document.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include "io/input_error.hpp"

namespace rigflex::io {
namespace {

int line_of(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

std::string place(const YAML::Node& n) {
  const YAML::Mark m = n.Mark();
  if (m.line < 0) return "an earlier line";
  return "line " + std::to_string(m.line + 1) + ", column " + std::to_string(m.column + 1);
}

// The first byte at which `text` stops being UTF-8 (YAML's encoding, and
// JSON's: a name that is not would pass through and stop the run at its
// very end, when the JSON output is written), or npos.
size_t invalid_utf8(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  for (size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    size_t len = 0;
    unsigned min = 0, cp = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      len = 2, min = 0x80, cp = c & 0x1Fu;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3, min = 0x800, cp = c & 0x0Fu;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4, min = 0x10000, cp = c & 0x07u;
    } else {
      return i;
    }
    if (i + len > n) return i;
    for (size_t k = 1; k < len; ++k) {
      if ((s[i + k] & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (s[i + k] & 0x3Fu);
    }
    // Overlong forms, surrogates and code points past Unicode are not UTF-8.
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += len;
  }
  return std::string::npos;
}

// Iterative (a hostile file may nest deeply) and bounded (aliases can make
// a small file a large tree).
void check_mappings(const YAML::Node& root, const std::string& source, long max_nodes) {
  // Each node with its path ("geometry.rods[2].upper", lists 1-based as the
  // readers name them), so that an error names the key in full.
  std::vector<std::pair<YAML::Node, std::string>> todo{{root, ""}};
  long visited = 0;
  while (!todo.empty()) {
    const auto [n, path] = todo.back();
    todo.pop_back();
    if (++visited > max_nodes) {
      throw InputError(source, line_of(n), "",
                       "the document expands to more than " + std::to_string(max_nodes) +
                           " nodes (aliases repeating a large part?)");
    }
    if (n.IsSequence()) {
      for (size_t i = 0; i < n.size(); ++i) todo.emplace_back(n[i], path + "[" + std::to_string(i + 1) + "]");
    } else if (n.IsMap()) {
      std::map<std::string, YAML::Node> seen;
      for (const auto& kv : n) {
        if (!kv.first.IsScalar()) {
          throw InputError(source, line_of(kv.first), path,
                           "a key must be a plain name or number, not a list or mapping");
        }
        const std::string key = kv.first.Scalar();
        const std::string full = path.empty() ? key : path + "." + key;
        const auto [it, fresh] = seen.emplace(key, kv.first);
        if (!fresh) {
          throw InputError(source, line_of(kv.first), full,
                           "given twice in the same mapping (first at " + place(it->second) +
                               "); only one can hold: remove the other");
        }
        todo.emplace_back(kv.second, full);
      }
    }
  }
}

}  // namespace

YAML::Node load_yaml(const std::string& text, const std::string& source, long max_nodes) {
  if (const size_t at = invalid_utf8(text); at != std::string::npos) {
    const size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
    const size_t column = line_start == std::string::npos ? at + 1 : at - line_start;
    const auto line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')) + 1;
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[at]));
    throw InputError(source, line, "",
                     "not UTF-8 at column " + std::to_string(column) + " (byte " + byte + "): save the file as UTF-8");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source, e.mark.line >= 0 ? e.mark.line + 1 : 0, "", "malformed YAML: " + e.msg);
  }
  check_mappings(root, source, max_nodes);
  return root;
}

InputError yaml_input_error(const std::string& source, const YAML::Exception& e) {
  if (dynamic_cast<const YAML::InvalidNode*>(&e) != nullptr) {
    // yaml-cpp's text: 'invalid node; first invalid key: "area"'.
    const std::string marker = "first invalid key: \"";
    const size_t at = e.msg.find(marker);
    const std::string key =
        at == std::string::npos
            ? ""
            : e.msg.substr(at + marker.size(), e.msg.find('"', at + marker.size()) - at - marker.size());
    return InputError(source, 0, key, "missing where it is needed, or not of the kind expected");
  }
  return InputError(source, e.mark.is_null() ? 0 : e.mark.line + 1, "", e.msg);
}

}  // namespace rigflex::io
