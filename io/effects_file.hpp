#pragma once
// The effects file (`rigflex compare --effects`, `rigflex diagnose`'s
// DIR/effects/<effect>.yaml): comment lines, then the one key `effects:`
// holding effect blocks as rig::effect_yaml writes them. Read back by
// io::add_effects (io/rig_reader.hpp).
#include <string>
#include <vector>

namespace rigflex::io {

// `comments` become "# " lines; `blocks` (rig::effect_yaml's text, at
// indent 0) are indented under `effects:`.
std::string effects_file_text(const std::vector<std::string>& comments, const std::string& blocks);

}  // namespace rigflex::io
