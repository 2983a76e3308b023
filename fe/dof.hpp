#pragma once
// Degrees of freedom: every node carries six, in this order, in global axes.
#include <array>
#include <optional>
#include <string_view>

namespace rigflex::fe {

inline constexpr int kDofsPerNode = 6;

enum class Dof : int { UX = 0, UY = 1, UZ = 2, RX = 3, RY = 4, RZ = 5 };

inline constexpr std::array<std::string_view, kDofsPerNode> kDofNames{"UX", "UY", "UZ",
                                                                      "RX", "RY", "RZ"};

inline std::string_view dof_name(int local_dof) { return kDofNames.at(static_cast<size_t>(local_dof)); }

// The local DOF (0..5) named "UX" .. "RZ", or nothing for any other text.
inline std::optional<int> dof_index(std::string_view name) {
  for (int k = 0; k < kDofsPerNode; ++k)
    if (kDofNames[static_cast<size_t>(k)] == name) return k;
  return std::nullopt;
}

}  // namespace rigflex::fe
