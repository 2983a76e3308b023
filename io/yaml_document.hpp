#pragma once
// Reading a YAML document as the readers need it: a parse error becomes an
// InputError at its line, and what yaml-cpp accepts but a reader cannot
// take without guessing is refused before any key is read. A key given
// twice in one mapping is the case that matters: yaml-cpp keeps both and a
// lookup silently returns the first, so `rho: 7850, rho: 1` or two
// materials of the same name would run with one of them dropped.
#include <yaml-cpp/yaml.h>

#include <string>

#include "io/input_error.hpp"

namespace rigflex::io {

// Parses `text` (named `source` in errors) and checks every mapping: keys
// are plain scalars, none given twice (both lines named). A document that
// expands past `max_nodes` through aliases is refused (the walk is bounded).
YAML::Node load_yaml(const std::string& text, const std::string& source, long max_nodes = 10'000'000);

// A yaml-cpp exception as the InputError of `source`: the key an invalid
// lookup names, or the line of a conversion's mark.
InputError yaml_input_error(const std::string& source, const YAML::Exception& e);

// Runs a reader's body. A yaml-cpp exception escaping it (a lookup the
// reader did not check first: found by fuzzing) becomes an InputError
// naming the file, never an internal error (exit 3) that names nothing.
template <class F>
decltype(auto) guard_yaml(const std::string& source, F&& read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw yaml_input_error(source, e);
  }
}

}  // namespace rigflex::io
