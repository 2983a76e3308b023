#pragma once
// What a command tells the user before a large solve, and the limit it holds
// it to (--max-memory): the assembled system's size from the model's
// connectivity, then the factor's from CHOLMOD's symbolic analysis.
#include <functional>
#include <optional>
#include <string>

#include "fe/assembly_size.hpp"
#include "io/rig_reader.hpp"
#include "linalg/sparse_cholesky.hpp"

namespace rigflex::app {

// The memory a run may use: --max-memory in GiB if given, else the machine's.
double memory_limit_bytes(std::optional<double> max_memory_gib);

// "assembling 120000 DOFs, 4.3e+06 nonzeros in K, about 150 MiB"
std::string assembly_line(const fe::AssemblySize& size);
// "factorizing: 2.1e+07 nonzeros in L, 170 MiB, 1.9e+10 flops (about 4 s)"
std::string factor_line(const linalg::FactorStatistics& s);

// A refusal's whole message: why (an estimate above the limit), where the
// limit comes from, and that nothing was written.
std::string memory_refusal(const std::string& why);

// Shows the assembly's progress on one stderr line ("assembled 1200 of
// 5000 elements"), ended at the last element.
std::function<void(long done, long total)> assembly_progress(const std::string& prefix = "");

// How the commands that read a rig file reduce its frames: the stages, each
// factorization's size and the assembly's progress told on stderr after
// "COMMAND: frame reduction: " (unless quiet), and every frame held to the
// machine's memory.
io::RigReadOptions frame_reduction_options(const std::string& command, bool quiet);

// Before a command assembles `model` (read from `model_file`): throws
// io::InputError naming the file when the assembly would pass the limit
// (fe::assembly_refusal), else tells the user the system's size on stderr
// (unless quiet), after `prefix` ("reduce: ").
void announce_assembly(const std::string& model_file, const fe::Model& model, double limit_bytes, bool quiet,
                       const std::string& prefix = "");

}  // namespace rigflex::app
