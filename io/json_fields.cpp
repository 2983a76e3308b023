#include "io/json_fields.hpp"

#include <algorithm>
#include <climits>
#include <fstream>
#include <iterator>

namespace rigflex::io {
namespace {

using json = nlohmann::json;

// Where nlohmann's lexer is. It reads one character at a time through the
// iterator and reports a key or a value as soon as the token ends (a number
// is followed by at most one extra character: a separator or a blank), so
// the line of the last non-blank character read is the line of the token.
struct LexerPosition {
  int line = 1;
  int token_line = 1;
};

class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* at, LexerPosition* position) : at_(at), position_(position) {}
  reference operator*() const { return *at_; }
  CountingIterator& operator++() {
    const char c = *at_++;
    if (c == '\n') ++position_->line;
    else if (c != ' ' && c != '\t' && c != '\r') position_->token_line = position_->line;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& other) const { return at_ == other.at_; }

 private:
  const char* at_;
  LexerPosition* position_;
};

std::string member_path(const std::string& object, const std::string& key) {
  return object.empty() ? key : object + "." + key;
}

// "[json.exception.parse_error.101] parse error at line 3, column 5: syntax
// error ..." -> "syntax error ...": the file and line are said by InputError.
std::string parse_reason(const std::string& what) {
  auto at = what.find("column ");
  if (at != std::string::npos) at = what.find(": ", at);
  return at == std::string::npos ? what : what.substr(at + 2);
}

}  // namespace

JsonFields::JsonFields(const std::string& text, std::string file) : file_(std::move(file)) {
  struct Frame {
    bool array = false;
    std::string path;
    std::string key;  // the key whose value comes next (objects)
    long index = -1;  // of the last element (arrays)
  };
  LexerPosition position;
  std::vector<Frame> open;
  auto next_path = [&]() -> std::string {
    if (open.empty()) return "";
    Frame& f = open.back();
    if (f.array) return f.path + "[" + std::to_string(++f.index) + "]";
    return member_path(f.path, f.key);
  };
  const json::parser_callback_t record = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start: {
        std::string path = next_path();
        lines_[path] = position.token_line;
        open.push_back({event == json::parse_event_t::array_start, std::move(path), "", -1});
        break;
      }
      case json::parse_event_t::key: open.back().key = parsed.get<std::string>(); break;
      case json::parse_event_t::value: lines_[next_path()] = position.token_line; break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end: open.pop_back(); break;
    }
    return true;
  };
  const CountingIterator first(text.data(), &position), last(text.data() + text.size(), &position);
  try {
    doc_ = json::parse(first, last, record);
  } catch (const json::parse_error& e) {
    const auto upto = std::min(text.size(), static_cast<size_t>(e.byte > 0 ? e.byte - 1 : 0));
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(upto), '\n'));
    throw InputError(file_, line, "", "malformed JSON: " + parse_reason(e.what()));
  } catch (const json::exception& e) {  // e.g. a number beyond the range of a double
    throw InputError(file_, position.token_line, "", "malformed JSON: " + parse_reason(e.what()));
  }
}

JsonFields JsonFields::from_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, 0, "", "cannot open the file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, 0, "", "cannot read the file");
  return JsonFields(text, file);
}

int JsonFields::line_of(const std::string& path) const {
  const auto it = lines_.find(path);
  return it == lines_.end() ? 0 : it->second;
}

void JsonFields::fail(const JsonNode& at, const std::string& message) const {
  throw InputError(file_, line_of(at.path), at.path, message);
}

void JsonFields::expect_object(const JsonNode& n, std::initializer_list<const char*> allowed) const {
  if (!n.value->is_object()) fail(n, std::string("expected an object, found ") + n.value->type_name());
  for (const auto& item : n.value->items()) {
    // Named, not a structured binding: clang 14 cannot capture one in a lambda.
    const std::string& key = item.key();
    const auto& value = item.value();
    if (std::find_if(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }) != allowed.end())
      continue;
    std::string names;
    for (const char* a : allowed) names.append(names.empty() ? "" : ", ").append(a);
    fail({&value, member_path(n.path, key)}, "unknown key; expected one of: " + names);
  }
}

JsonNode JsonFields::required(const JsonNode& object, const std::string& key) const {
  if (!object.value->is_object()) fail(object, std::string("expected an object, found ") + object.value->type_name());
  const auto it = object.value->find(key);
  const std::string path = member_path(object.path, key);
  if (it == object.value->end()) throw InputError(file_, line_of(object.path), path, "missing");
  return {&*it, path};
}

std::vector<JsonNode> JsonFields::elements(const JsonNode& array) const {
  if (!array.value->is_array()) fail(array, std::string("expected an array, found ") + array.value->type_name());
  std::vector<JsonNode> out;
  out.reserve(array.value->size());
  for (size_t i = 0; i < array.value->size(); ++i)
    out.push_back({&(*array.value)[i], array.path + "[" + std::to_string(i) + "]"});
  return out;
}

std::vector<JsonNode> JsonFields::elements(const JsonNode& array, size_t count) const {
  auto out = elements(array);
  if (out.size() != count)
    fail(array, "expected " + std::to_string(count) + " values, found " + std::to_string(out.size()));
  return out;
}

double JsonFields::number(const JsonNode& n) const {
  if (n.value->is_null()) fail(n, "expected a number, found null (NaN and infinities are never written)");
  if (!n.value->is_number()) fail(n, std::string("expected a number, found ") + n.value->type_name());
  return n.value->get<double>();
}

long JsonFields::integer(const JsonNode& n) const {
  if (!n.value->is_number_integer()) fail(n, "expected an integer, found " + (n.value->is_number() ? n.value->dump() : std::string(n.value->type_name())));
  if (n.value->is_number_unsigned() && n.value->get<json::number_unsigned_t>() > static_cast<unsigned long>(LONG_MAX))
    fail(n, "integer too large");
  return n.value->get<long>();
}

bool JsonFields::boolean(const JsonNode& n) const {
  if (!n.value->is_boolean()) fail(n, std::string("expected true or false, found ") + n.value->type_name());
  return n.value->get<bool>();
}

std::string JsonFields::text(const JsonNode& n) const {
  if (!n.value->is_string()) fail(n, std::string("expected a string, found ") + n.value->type_name());
  return n.value->get<std::string>();
}

}  // namespace rigflex::io
