#pragma once
// The size of a model's assembled system, counted from its connectivity
// before anything is assembled: what a command prints, and checks against
// the memory it may use, before it commits to the work.
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

}  // namespace rigflex::fe
