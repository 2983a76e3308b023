#pragma once
// The size of a model's assembled system, counted from its connectivity
// before anything is assembled: what a command prints, and checks against
// the memory it may use, before it commits to the work.
#include <string>

#include "fe/model.hpp"

namespace rigflex::fe {

struct AssemblySize {
  long dofs = 0;        // 6 per node that an element, spring, mass or coupling uses
  double nonzeros = 0;  // of K over those DOFs, both triangles (M has the same pattern or fewer)
  // K and M as compressed columns (8-byte values, 4-byte row indices), plus
  // the largest batch of element contributions the assembly holds at once.
  double bytes = 0;
};

// Two nodes couple when an element, a two-node spring or a rigid coupling
// holds both; the count is exact for the full matrix (all six DOFs of every
// coupled node pair), an upper bound for the free one (supports remove rows,
// dropped rotations fewer).
AssemblySize assembly_size(const Model& model);

// "12.3 MiB", "4.10 GiB".
std::string bytes_text(double bytes);

// Why the assembly would pass `limit_bytes` ("the model's 98826 DOFs and
// 5.28e+06 nonzeros need about 246.3 MiB to assemble, above the limit of
// 204.8 MiB"); empty if it fits or there is no limit (0).
std::string assembly_refusal(const AssemblySize& size, double limit_bytes);

}  // namespace rigflex::fe
