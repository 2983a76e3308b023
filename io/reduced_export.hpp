#pragma once
// The lossless export of a reduced frame (reduction/reduced_model.hpp) into a
// folder, and its reader. The files (docs/reduction-formats.md):
//   reduced.json                          everything but the matrices, and the list of files
//   K.mtx M.mtx C.mtx                     reduced stiffness, mass, damping (Matrix Market)
//   ss_A.mtx ss_B.mtx ss_C.mtx ss_D.mtx   the state-space form
//   ss_T.mtx                              its coordinates: z = T xi, x = [xi; xi']
//   reduced.mat                           the same for MATLAB / Simscape (io/reduced_mat.hpp)
// Every double reads back bit for bit: the matrices carry 17 significant
// digits, JSON numbers are written as the shortest decimal that reads back
// to the same double. NaN and infinities have no JSON spelling, so a frame
// holding one anywhere is refused rather than written with a null.
#include <nlohmann/json.hpp>

#include <filesystem>

#include "io/atomic_file.hpp"
#include "reduction/reduced_model.hpp"

namespace rigflex::io {

inline constexpr const char* kReducedFrameFormat = "rigflex-reduced-frame";
// Version 2 added the state space's coordinates (ss_T.mtx, state_space.coordinates
// and rigid_body_modes); version 1 folders are still read (physical coordinates).
inline constexpr int kReducedFrameVersion = 2;

// Throws std::invalid_argument naming the field when `r` cannot be exported
// as it is: matrix sizes that contradict the interface DOFs and mode count,
// a NaN or infinity anywhere, repeated interface nodes or DOFs, a DOF of a
// node outside the interface, a rotation when `retained` is translations,
// an interface node that keeps no DOF, a reference node without FrameSupport::reference_node (or
// the reverse), a node id beyond 2^53 (reduced.mat holds ids as doubles),
// names that are not UTF-8.
void check_exportable(const reduction::ReducedFrame& r);

// reduced.json's content, unchecked.
nlohmann::ordered_json reduced_frame_json(const reduction::ReducedFrame& r);

// Adds every file of the export of `r` into `dir` to `batch`, reduced.json
// last so that it never names a matrix file that is not there yet; the
// caller commits. Checks `r` first (check_exportable): a frame that cannot
// be exported adds nothing.
void add_reduced_frame_files(FileBatch& batch, const std::filesystem::path& dir, const reduction::ReducedFrame& r);
// add_reduced_frame_files and commit.
void write_reduced_frame(const std::filesystem::path& dir, const reduction::ReducedFrame& r);

// Reads DIR/reduced.json and the Matrix Market files it lists (reduced.mat
// is not read: see read_reduced_mat). Throws InputError naming the file, the
// line and the key: a missing or unknown key, a wrong type, another format
// or version, values that contradict each other (as check_exportable), a
// file name with a folder in it, a matrix file whose size differs from what
// reduced.json implies (named at its size line) or that is malformed.
reduction::ReducedFrame read_reduced_frame(const std::filesystem::path& dir);

}  // namespace rigflex::io
