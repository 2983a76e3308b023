#pragma once
// A reduced frame in the matrix formats of the solvers users already run:
// Nastran DMIG cards and Abaqus *MATRIX INPUT files (docs/reduction-formats.md).
// Interface DOFs keep their node ids and directions; each Craig-Bampton modal
// coordinate gets an id of its own above every interface node id (a Nastran
// SPOINT, an Abaqus node's DOF 1), so the reduced frame joins the user's model
// at the interface nodes.
#include <map>
#include <string>

#include "reduction/reduced_model.hpp"

namespace rigflex::io {

// The first id given to a modal coordinate: the next power of ten above the
// largest interface node id (at least 1000), so it reads as a separate range.
long modal_coordinate_base(const reduction::ReducedFrame& r);

// KAAX, MAAX and BAAX (stiffness, mass, damping) as symmetric (IFO 6), real
// double (TIN 2) DMIG matrices in large-field format, each pair of DOFs once
// (the upper triangle in Nastran's sort order: grid or scalar point id, then
// component); SPOINT cards for the modal coordinates. For K2GG = KAAX,
// M2GG = MAAX, B2GG = BAAX in the case control.
std::string nastran_dmig(const reduction::ReducedFrame& r);

// Abaqus: `<stem>.inp` (a *NODE block for the modal coordinates' nodes and
// *MATRIX INPUT / *MATRIX ASSEMBLE of the matrices) and `<stem>_K.txt`,
// `<stem>_M.txt`, `<stem>_C.txt` in Abaqus's matrix input format: "row node,
// row DOF, column node, column DOF, value", the lower triangle. File name ->
// text.
std::map<std::string, std::string> abaqus_matrix_files(const reduction::ReducedFrame& r, const std::string& stem);

}  // namespace rigflex::io
