#pragma once
// YAML to the effect catalogue's parameter tree (rig/effect_parameters.hpp):
// every node with its line, scalars with the number yaml-cpp reads in them,
// so that the catalogue's reads fail with io::YamlContext's messages.
#include <yaml-cpp/yaml.h>

#include "rig/effect_parameters.hpp"

namespace rigflex::io {

rig::ParameterValue parameter_tree(const YAML::Node& node);

}  // namespace rigflex::io
