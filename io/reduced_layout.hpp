#pragma once
// The layout of a reduced-frame export folder, shared by its writer
// (reduced_export.cpp, reduced_mat.cpp) and its reader (reduced_import.cpp).
#include <nlohmann/json.hpp>

#include <array>
#include <string_view>

#include "reduction/reduced_model.hpp"

namespace rigflex::io::reduced_layout {

inline constexpr const char* kJsonFile = "reduced.json";
inline constexpr const char* kMatFile = "reduced.mat";
inline constexpr const char* kMatKey = "mat";  // its key in reduced.json's "files"

struct MatrixFile {
  const char* key;   // in reduced.json's "files"
  const char* file;  // the name written
  const char* what;  // the file's comment lines
};

inline constexpr std::array<MatrixFile, 8> kMatrixFiles{{
    {"K", "K.mtx",
     "reduced stiffness K (N/m, N m/rad)\n"
     "rows and columns: z, the interface DOFs in the dof_order of reduced.json, then the modal coordinates"},
    {"M", "M.mtx",
     "reduced mass M (kg, kg m^2)\n"
     "rows and columns: z, the interface DOFs in the dof_order of reduced.json, then the modal coordinates"},
    {"C", "C.mtx",
     "reduced damping C (N s/m, N m s/rad), Rayleigh: see damping in reduced.json\n"
     "rows and columns: z, the interface DOFs in the dof_order of reduced.json, then the modal coordinates"},
    {"ss_A", "ss_A.mtx",
     "state-space A of x' = A x + B u, y = C x + D u\n"
     "rows and columns: x = [xi; xi'], z = T xi (ss_T.mtx; state_space.coordinates in reduced.json)"},
    {"ss_B", "ss_B.mtx",
     "state-space B of x' = A x + B u, y = C x + D u\n"
     "rows: x = [xi; xi']; columns: u, forces and moments at the interface DOFs in the dof_order of reduced.json"},
    {"ss_C", "ss_C.mtx",
     "state-space C of x' = A x + B u, y = C x + D u\n"
     "rows: y = [interface displacements; interface velocities] in the dof_order of reduced.json; columns: x = [xi; "
     "xi']"},
    {"ss_D", "ss_D.mtx",
     "state-space D of x' = A x + B u, y = C x + D u\n"
     "rows: y = [interface displacements; interface velocities]; columns: u, the interface forces and moments"},
    {"ss_T", "ss_T.mtx",
     "state-space coordinates: z = T xi, x = [xi; xi'] the state of ss_A\n"
     "rows: z, the interface DOFs in the dof_order of reduced.json, then the modal coordinates; columns: xi (the "
     "identity for physical coordinates; for modal ones the M-orthonormal modes, rigid-body modes first)"},
}};

// The matrix of `r` that a MatrixFile key names (const or not, as `r`).
template <class Frame>
auto& matrix(Frame& r, std::string_view key) {
  if (key == "K") return r.K;
  if (key == "M") return r.M;
  if (key == "C") return r.C;
  if (key == "ss_A") return r.state_space.A;
  if (key == "ss_B") return r.state_space.B;
  if (key == "ss_C") return r.state_space.C;
  if (key == "ss_D") return r.state_space.D;
  return r.state_space.T;
}

// Rows and columns of each matrix for n reduced coordinates and m interface DOFs.
struct MatrixSize {
  Eigen::Index rows, cols;
};
inline MatrixSize matrix_size(std::string_view key, Eigen::Index n, Eigen::Index m) {
  if (key == "ss_A") return {2 * n, 2 * n};
  if (key == "ss_B") return {2 * n, m};
  if (key == "ss_C") return {2 * m, 2 * n};
  if (key == "ss_D") return {2 * m, m};
  return {n, n};  // K, M, C, ss_T
}

// The only units written or read.
inline nlohmann::ordered_json units_json() {
  return {{"system", "SI"}, {"length", "m"},  {"angle", "rad"},    {"mass", "kg"},
          {"time", "s"},    {"force", "N"},   {"moment", "N m"},   {"frequency", "Hz"},
          {"angular_frequency", "rad/s"}};
}

}  // namespace rigflex::io::reduced_layout
