#pragma once
// Reads a rig file (rig.yaml) into a rig::RigModel, strictly: the spec's
// geometry block exactly, the body's mass properties record, sensors, release
// protocol, integrator settings and effects under the spec's names. Errors
// are InputErrors naming the file, line and key. Frames that an effect makes
// flexible are read from `rigflex reduce` exports or reduced in-process from
// a frame model. The format is documented in docs/rig.md.
#include <filesystem>
#include <functional>
#include <string>

#include "rig/rig_model.hpp"

namespace rigflex::io {

struct RigReadOptions {
  std::function<void(const std::string&)> progress;  // in-process reductions report here
};

rig::RigModel read_rig(const std::filesystem::path& file, const RigReadOptions& options = {});
// `source` names the text in errors; relative paths inside resolve against `base`.
rig::RigModel parse_rig(const std::string& yaml_text, const std::string& source, const std::filesystem::path& base,
                        const RigReadOptions& options = {});

}  // namespace rigflex::io
