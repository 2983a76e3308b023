#pragma once
// NAFEMS FV52 (R0015, "simply supported solid square plate"): 10 m x 10 m x
// 1 m steel (E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3), UZ = 0 along the four
// edges of the lower face, nothing else: three in-plane rigid-body modes,
// then the targets below as modes 4-10. Shared by the solid elements'
// verification tests and bench/bench_solid_modes.
#include <array>
#include <string>

#include "fe/model.hpp"

namespace rigflex::verification {

inline constexpr std::array<double, 7> kFv52TargetsHz{45.897, 109.44, 109.44, 167.89, 193.59, 206.19, 206.19};
inline constexpr int kFv52RigidModes = 3;

// The plate meshed as one solid block of `element` (a fe::solid_types()
// name), n x n cells in plane and nz through the thickness.
fe::Model nafems_fv52(const std::string& element, int n, int nz);

}  // namespace rigflex::verification
