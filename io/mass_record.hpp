#pragma once
// The spec's mass properties record (shared/spec/rig-conventions.md):
// `mass`, `cog`, `inertia` [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] about the CoG,
// negative-integral products; `std` in the same shape where known. Read from
// YAML or JSON (a tare, a static reference); an identification.json is read
// through its `mean`.
#include <nlohmann/json.hpp>
#include <array>
#include <filesystem>
#include <optional>

#include "fe/mass_properties.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {

// InputError naming the file, line and key for anything else.
fe::MassProperties read_mass_record(const std::filesystem::path& file);
fe::MassProperties parse_mass_record(const std::string& text, const std::string& source);

// Standard deviations in the record's shape: mass, xG yG zG, then the six inertia components.
struct MassRecordStd {
  double mass = 0;
  std::array<double, 3> cog{};
  std::array<double, 6> inertia{};
};
// The spec's mass properties record as modes.json and reduced.json carry it:
// mass, cog, inertia [Jxx Jyy Jzz Jxy Jxz Jyz], keys sorted.
nlohmann::json mass_properties_json(const fe::MassProperties& p);
nlohmann::ordered_json mass_record_json(const fe::MassProperties& p, const std::optional<MassRecordStd>& std = {});

}  // namespace rigflex::io
