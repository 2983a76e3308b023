#pragma once
// Reads a rig file (rig.yaml), strictly: the spec's geometry block exactly,
// the body's mass properties record, sensors, release protocol, integrator
// settings and effects under the spec's names. Errors are InputErrors naming
// the file, line and key. Reading is pure (rig/rig_spec.hpp): frames that an
// effect makes flexible are read from `rigflex reduce` exports or as frame
// models, and rig::resolve_frames reduces them and places them on the joints.
// The format is documented in docs/rig.md.
#include <filesystem>
#include <functional>
#include <string>

#include "io/input_error.hpp"
#include "rig/rig_model.hpp"
#include "rig/rig_spec.hpp"

namespace rigflex::io {

// How in-process reductions of the rig's frames report and what memory they
// may take (rig::FrameResolveOptions).
using RigReadOptions = rig::FrameResolveOptions;

// What the file says, frames not yet reduced.
rig::RigSpec read_rig_spec(const std::filesystem::path& file);
// `source` names the text in errors; relative paths inside resolve against `base`.
rig::RigSpec parse_rig_spec(const std::string& yaml_text, const std::string& source,
                            const std::filesystem::path& base);
// rig::resolve_frames, its errors as the InputErrors of the rig file's keys.
rig::RigModel resolve_rig(const rig::RigSpec& spec, const RigReadOptions& options = {});

// read_rig_spec and resolve_rig in one.
rig::RigModel read_rig(const std::filesystem::path& file, const RigReadOptions& options = {});
// `source` names the text in errors; relative paths inside resolve against `base`.
rig::RigModel parse_rig(const std::string& yaml_text, const std::string& source, const std::filesystem::path& base,
                        const RigReadOptions& options = {});

// Adds (or replaces, by name) the effects of a file holding one key,
// `effects`, in the rig file's form: what `rigflex diagnose` writes for a
// fitted effect. Relative paths resolve against the file's folder.
void add_effects(rig::RigModel& model, const std::filesystem::path& file, const RigReadOptions& options = {});

// The error for a rig read from `file` whose static equilibrium was not found
// (rig::NoEquilibrium, message `detail`, from the check or the simulation):
// names the file and the line and key of the likeliest cause. That is
// release.initial when an initial condition could not be held, else the first
// effect switched on that changes the rig's statics (rod_compliance,
// fixed_frame_flexibility, carrying_frame_flexibility, rod_length_error,
// joint_position_error), else geometry. A rigid rig of valid geometry always
// has one.
InputError no_equilibrium_error(const std::filesystem::path& file, const rig::RigModel& model,
                                const std::string& detail);

}  // namespace rigflex::io
