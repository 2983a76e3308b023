#pragma once
// The rig's linear modes for ParaView: a skeleton of the rig (upper joints,
// rods, lower joints, reference point and CoG) with each mode's motion as
// point data `translation`, scaled for display (the largest kDisplayShare of
// the mean rod length; the factor in the field `display_scale`, as for the
// frames' modes in io/vtk_modes.hpp); one .vtu per mode and DIR/rig_modes.pvd.
#include <filesystem>

#include "io/atomic_file.hpp"
#include "rig/linearization.hpp"

namespace rigflex::io {

void add_rig_mode_files(FileBatch& batch, const std::filesystem::path& dir, const rig::RigSystem& rig,
                        const rig::Linearization& lin);

}  // namespace rigflex::io
