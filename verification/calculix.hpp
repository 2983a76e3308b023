#pragma once
// CalculiX (ccx 2.20) input for a *FREQUENCY analysis of a frame model, and a
// runner that calls `ccx` on it and reads the eigenvalue table back: the
// independent cross-check of rigflex's elements, assembly and eigen solver.
//
// The deck and how each part of a model maps onto ccx: io/calculix_deck.hpp.
#include <Eigen/Sparse>
#include <filesystem>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "fe/model.hpp"
#include "io/calculix_deck.hpp"

namespace rigflex::verification {

// The deck writer is a user feature (rigflex export): io/calculix_deck.hpp.
using io::calculix_deck;
using io::calculix_input;
using io::CalculixDeck;
using io::CalculixDialect;
using io::CalculixOptions;

struct CalculixFrequencies {
  std::vector<double> eigenvalues;     // (rad/s)^2, as ccx prints them
  std::vector<double> frequencies_hz;  // ccx's "real part, cycles/time" column
  double wall_seconds = 0.0;           // the ccx process alone (not writing the .inp)
  double write_seconds = 0.0;          // writing job.inp
  long max_rss_kb = 0;                 // peak resident set of the ccx process (wait4)
  long equations = 0;                  // size of ccx's (expanded, 3D) system, from its log; 0 if not found
  std::filesystem::path input, dat, log;
};

struct CalculixRunOptions {
  std::string executable = "ccx";  // looked up on PATH
  std::string job = "job";
  // > 0: sets OMP_NUM_THREADS and CCX_NPROC_* for the child; 0: inherit.
  int threads = 0;
};

// Writes <work_dir>/job.inp, runs `ccx -i job` in work_dir (stdout and
// stderr to job.log), parses the eigenvalue table of job.dat. Throws
// std::runtime_error (with the tail of ccx's output) if ccx cannot be
// started, fails, or prints no eigenvalue table; the error names job.log.
CalculixFrequencies run_calculix_frequencies(const fe::Model& model, int count,
                                             const std::filesystem::path& work_dir);
CalculixFrequencies run_calculix_frequencies(const fe::Model& model, int count,
                                             const std::filesystem::path& work_dir,
                                             const CalculixRunOptions& run);

// Runs `ccx -i <run.job>` in work_dir on a <run.job>.inp that is already
// there (a user's deck, with its *INCLUDE files beside it) and reads its
// eigenvalue table; errors as run_calculix_frequencies.
CalculixFrequencies run_calculix_job(const std::filesystem::path& work_dir, const CalculixRunOptions& run);

// Parses the "E I G E N V A L U E   O U T P U T" table of a ccx .dat text
// (exposed for tests). Throws std::runtime_error if there is none.
void parse_calculix_eigenvalues(const std::string& dat_text, std::vector<double>& eigenvalues,
                                std::vector<double>& frequencies_hz);

// ---------------------------------------------------------------------------
// ccx's own stiffness and mass: the step is written as *FREQUENCY,
// SOLVER=MATRIXSTORAGE, and ccx 2.20 (matrixstorage.c) writes, instead of
// solving, the matrices of its expanded 3D system:
//   job.sti, job.mas  one entry per line, "row column value" (1-based,
//                     "%d %d %20.13e"), the diagonal and the upper triangle
//                     (row <= column) of the symmetric matrix, every entry of
//                     the sparsity pattern (structural zeros included), sorted
//                     by column, then row. Unshifted K and M (the eigen
//                     shift is applied by the factorizing solvers only).
//   job.dof           one line per row/column, "node.direction".
// The system is the one ccx solves: *BOUNDARY DOFs are removed and
// *EQUATION (and ccx's own knot and expansion MPC) dependents eliminated
// exactly (K <- T' K T, M <- T' M T), so neither appears in job.dof. Found by
// running ccx 2.20 on small models:
//   * the DOFs of the 3D nodes that ccx expands a beam or shell node into
//     are labelled with that beam/shell node's number (8 nodes at a B32R end
//     node, 4 at its mid node): a label then occurs several times per
//     direction and is no DOF of the beam node itself;
//   * where ccx makes a "knot" (members meeting at an angle; the writer's
//     anchors make one at coupled beam and shell nodes), the expanded nodes
//     follow a rigid body and are eliminated, and the beam node's own
//     translations are DOFs, each label once; the knot's rotations are the
//     translations of a node ccx generates (numbered after the deck's
//     nodes), and one more generated node carries the knot's stretch (a
//     single DOF, direction 1, for a B32R knot);
//   * nodes outside beams and shells (coupling references, point-mass
//     nodes, the writer's rotation nodes) keep their own DOFs.
using CalculixSparse = Eigen::SparseMatrix<double, Eigen::ColMajor>;

// Where a ccx node number comes from.
enum class CalculixNodeOrigin {
  model,   // a node of the rigflex model (its id in CalculixDof::model_node)
  writer,  // generated by the writer: B32R mid nodes, coupling rotation nodes,
           // knot anchors, spring anchors
  ccx,     // generated by ccx: knot rotation and expansion nodes
};

struct CalculixDof {
  long ccx_node = 0;   // the label in job.dof
  int direction = 0;   // 1..3 (translations); 0 would be a temperature
  CalculixNodeOrigin origin = CalculixNodeOrigin::ccx;
  fe::NodeId model_node = 0;  // rigflex id when origin == model, else 0
};

struct CalculixMatrices {
  CalculixSparse K, M;            // symmetric, both triangles stored, SI units
  std::vector<CalculixDof> dofs;  // one per row, in ccx's order
  double wall_seconds = 0.0;      // the ccx process alone
  std::filesystem::path input, stiffness, mass, dof_file, log;

  // The row of the model node's own translation `direction` (1..3): the one
  // row with that label, or std::nullopt when the label is absent (held or
  // eliminated) or occurs more than once (the expanded nodes of a beam or
  // shell node that is no knot, see above).
  std::optional<Eigen::Index> row_of(fe::NodeId node, int direction) const;
};

// Writes <work_dir>/<job>.inp with SOLVER=MATRIXSTORAGE, runs ccx there and
// reads job.sti, job.mas and job.dof back, labelling each row with the
// rigflex node it belongs to (the writer keeps rigflex ids as ccx node
// numbers when they fit, else renumbers; see calculix_input). Throws
// std::invalid_argument for bad run options or what the writer refuses;
// std::runtime_error if ccx fails (naming the log, with its tail) or a file
// is missing or malformed (naming the file and line).
CalculixMatrices run_calculix_matrices(const fe::Model& model, const std::filesystem::path& work_dir);
CalculixMatrices run_calculix_matrices(const fe::Model& model, const std::filesystem::path& work_dir,
                                       const CalculixRunOptions& run);

// Parsers of the three files (exposed for tests). `file` only names the
// source in error messages, as "file:line: reason" (std::runtime_error).
// parse_calculix_dofs returns (node, direction) per line;
// parse_calculix_matrix returns the symmetric size x size matrix and refuses
// indices outside 1..size, entries below the diagonal, repeated entries and
// non-finite values.
std::vector<std::pair<long, int>> parse_calculix_dofs(const std::string& text, const std::string& file);
CalculixSparse parse_calculix_matrix(const std::string& text, Eigen::Index size, const std::string& file);

// True if `executable` is found on PATH (or is an existing path).
bool calculix_available(const std::string& executable = "ccx");

}  // namespace rigflex::verification
