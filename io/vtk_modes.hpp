#pragma once
// Mode shapes for ParaView: one .vtu per mode (VTK XML unstructured grid:
// beams as lines, shells as quads, point masses as vertices; translations and
// rotations as point data, frequency as field data) and a .pvd collection.
#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

#include "fe/assembly.hpp"
#include "fe/model.hpp"
#include "io/atomic_file.hpp"

namespace rigflex::io {

// Queues DIR/modes.pvd and DIR/mode_NNN.vtu into `batch`.
void add_mode_shape_files(FileBatch& batch, const std::filesystem::path& dir, const fe::Model& model,
                          const fe::DofMap& dofs, const Eigen::VectorXd& frequencies_hz,
                          const Eigen::MatrixXd& vectors);

// A ParaView collection (.pvd) of one file per mode, named with its frequency.
std::string mode_collection(const Eigen::VectorXd& frequencies_hz, const std::vector<std::string>& files);

}  // namespace rigflex::io
