// rigflex mass MODEL.yaml: total mass, CoG and inertia tensor of a model.
#include <cstdio>
#include <iostream>

#include "apps/commands.hpp"
#include "fe/mass_properties.hpp"
#include "io/model_reader.hpp"
#include "io/mass_record.hpp"

namespace rigflex::app {

void add_mass_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("mass", "Mass, CoG and inertia tensor (about the CoG) of a model");
  auto file = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("model", *file, "model file (.yaml, or an Abaqus / CalculiX .inp deck)")->required();
  cmd->add_flag("--json", *json, "print the mass properties record as JSON");
  cmd->callback([file, json, &exit_code] {
    const io::ModelFile m = io::read_model(*file);
    const fe::MassProperties p = fe::mass_properties(m.model);
    if (*json) {
      std::cout << io::mass_properties_json(p).dump(2) << "\n";
    } else {
      const auto& J = p.inertia;
      std::printf("model: %s\n", m.name.c_str());
      std::printf("mass        %14.6g kg\n", p.mass);
      std::printf("cog         %14.6g %14.6g %14.6g m\n", p.cog.x(), p.cog.y(), p.cog.z());
      std::printf("inertia about the CoG [kg m^2], products Jxy = -integral(x y dm):\n");
      std::printf("  Jxx %14.6g  Jyy %14.6g  Jzz %14.6g\n", J(0, 0), J(1, 1), J(2, 2));
      std::printf("  Jxy %14.6g  Jxz %14.6g  Jyz %14.6g\n", J(0, 1), J(0, 2), J(1, 2));
    }
    exit_code = 0;
  });
}

}  // namespace rigflex::app
