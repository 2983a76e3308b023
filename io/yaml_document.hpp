#pragma once
// Reading a YAML document as the readers need it: a parse error becomes an
// InputError at its line, and what yaml-cpp accepts but a reader cannot
// take without guessing is refused before any key is read. A key given
// twice in one mapping is the case that matters: yaml-cpp keeps both and a
// lookup silently returns the first, so `rho: 7850, rho: 1` or two
// materials of the same name would run with one of them dropped.
#include <yaml-cpp/yaml.h>

#include <string>

namespace rigflex::io {

// Parses `text` (named `source` in errors) and checks every mapping: keys
// are plain scalars, none given twice (both lines named). A document that
// expands past `max_nodes` through aliases is refused (the walk is bounded).
YAML::Node load_yaml(const std::string& text, const std::string& source, long max_nodes = 10'000'000);

}  // namespace rigflex::io
