#pragma once
// Mode shapes for ParaView: one .vtu per mode (VTK XML unstructured grid:
// beams as lines, shells as quads, point masses as vertices; translations and
// rotations as point data, frequency as field data) and a .pvd collection.
// The shapes are scaled for display (ParaView's Warp By Vector at its
// factor 1 shows them): `translation` and `rotation` are the
// mass-normalized shape times the field `display_scale`; divide by it for
// the mass-normalized values. The rig's modes (io/rig_vtk.hpp) follow the
// same names and rule.
#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

#include "fe/assembly.hpp"
#include "fe/model.hpp"
#include "io/atomic_file.hpp"

namespace rigflex::io {

// The largest motion a display shape shows: this share of the model's size
// (its largest extent; the mean rod length for the rig).
inline constexpr double kDisplayShare = 0.05;

// The factor that makes the largest motion of `shape` (6 DOFs per node,
// UX UY UZ RX RY RZ; a rotation counts times `extent`, as at the model's far
// end) kDisplayShare x `extent`; 1 for a shape that does not move.
double display_scale(const Eigen::VectorXd& shape, double extent);

// Queues DIR/modes.pvd and DIR/mode_NNN.vtu into `batch`.
void add_mode_shape_files(FileBatch& batch, const std::filesystem::path& dir, const fe::Model& model,
                          const fe::DofMap& dofs, const Eigen::VectorXd& frequencies_hz,
                          const Eigen::MatrixXd& vectors);

// A ParaView collection (.pvd) of one file per mode, named with its frequency.
std::string mode_collection(const Eigen::VectorXd& frequencies_hz, const std::vector<std::string>& files);

}  // namespace rigflex::io
