#include "io/mass_record.hpp"

#include <fstream>
#include <sstream>

#include "io/yaml_document.hpp"
#include "io/yaml_fields.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::io {

static fe::MassProperties parse_mass_record_unguarded(const std::string& text, const std::string& source) {
  YAML::Node root = load_yaml(text, source);
  const YamlContext ctx(source);
  if (root.IsMap() && root["mean"]) root = root["mean"];  // an identification.json
  // What identify writes beside the record in its `mean` is accepted and not used.
  ctx.expect_map(root, "mass properties record",
                 {"mass", "cog", "inertia", "std", "name", "confidence_interval_95", "principal_moments",
                  "principal_axes"});
  fe::MassProperties p;
  p.mass = ctx.number(root, "mass");
  if (!(p.mass > 0)) ctx.fail(root["mass"], "mass", "must be positive");
  p.cog = ctx.vec3(root, "cog");
  const auto J = ctx.numbers(root, "inertia", 6);
  p.inertia = rig::inertia_tensor({J[0], J[1], J[2], J[3], J[4], J[5]});
  return p;
}

fe::MassProperties parse_mass_record(const std::string& text, const std::string& source) {
  return guard_yaml(source, [&] { return parse_mass_record_unguarded(text, source); });
}

fe::MassProperties read_mass_record(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), 0, "", "cannot open the mass properties record");
  std::stringstream text;
  text << in.rdbuf();
  return parse_mass_record(text.str(), file.string());
}

nlohmann::ordered_json mass_record_json(const fe::MassProperties& p, const std::optional<MassRecordStd>& std) {
  nlohmann::ordered_json j;
  j["mass"] = p.mass;
  j["cog"] = {p.cog.x(), p.cog.y(), p.cog.z()};
  const auto J = rig::inertia_components(p.inertia);
  j["inertia"] = J;
  if (std) j["std"] = {{"mass", std->mass}, {"cog", std->cog}, {"inertia", std->inertia}};
  return j;
}

nlohmann::json mass_properties_json(const fe::MassProperties& p) {
  const auto& J = p.inertia;
  return {{"mass", p.mass},
          {"cog", {p.cog.x(), p.cog.y(), p.cog.z()}},
          {"inertia", {J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2)}}};
}

}  // namespace rigflex::io
