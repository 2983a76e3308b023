#pragma once
// What a command tells the user before a large solve, and the limit it holds
// it to (--max-memory): the assembled system's size from the model's
// connectivity, then the factor's from CHOLMOD's symbolic analysis.
#include <optional>
#include <string>

#include "fe/assembly_size.hpp"
#include "linalg/sparse_cholesky.hpp"

namespace rigflex::app {

// The memory a run may use: --max-memory in GiB if given, else the machine's.
double memory_limit_bytes(std::optional<double> max_memory_gib);

// "12.3 MiB", "4.10 GiB".
std::string bytes_text(double bytes);

// "assembling 120000 DOFs, 4.3e+06 nonzeros in K, about 150 MiB"
std::string assembly_line(const fe::AssemblySize& size);
// "factorizing: 2.1e+07 nonzeros in L, 170 MiB, 1.9e+10 flops (about 4 s)"
std::string factor_line(const linalg::FactorStatistics& s);

// The refusal when the assembly alone would pass the limit; empty if it fits.
std::string assembly_refusal(const fe::AssemblySize& size, double limit_bytes);

}  // namespace rigflex::app
