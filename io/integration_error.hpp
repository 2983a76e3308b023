#pragma once
// An integrator failure told the user (the command line throws it): the files the model came from, the
// effects in it, where in time it stopped and what to try.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "rig/integration.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::io {

// model_files: the rig file, then any effects files added to it.
std::runtime_error integration_error(const rig::IntegrationFailure& e, const rig::RigModel& model,
                                     const std::vector<std::filesystem::path>& model_files);

}  // namespace rigflex::io
