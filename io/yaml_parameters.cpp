#include "io/yaml_parameters.hpp"

#include "io/yaml_fields.hpp"

namespace rigflex::io {

rig::ParameterValue parameter_tree(const YAML::Node& node) {
  using Kind = rig::ParameterValue::Kind;
  rig::ParameterValue v;
  if (!node.IsDefined()) return v;
  v.line = YamlContext::line_of(node);
  if (node.IsNull()) {
    v.kind = Kind::null;
  } else if (node.IsScalar()) {
    v.kind = Kind::scalar;
    v.text = node.Scalar();
    double x = 0.0;
    if (YAML::convert<double>::decode(node, x)) v.number = x;
  } else if (node.IsSequence()) {
    v.kind = Kind::list;
    for (const auto& e : node) v.items.push_back(parameter_tree(e));
  } else if (node.IsMap()) {
    v.kind = Kind::map;
    for (const auto& kv : node) {
      v.entries.push_back({kv.first.as<std::string>(), YamlContext::line_of(kv.first), parameter_tree(kv.second)});
    }
  }
  return v;
}

}  // namespace rigflex::io
