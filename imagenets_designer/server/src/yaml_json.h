// YAML <-> JSON for the few places where the Designer shows or takes a piece of a net file as
// JSON (a block's feedback map): plain scalars that read as numbers or booleans become JSON
// numbers / booleans, quoted scalars stay strings.
#pragma once

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace imagenets {
namespace designer {

nlohmann::json yamlToJson(const YAML::Node& node);
YAML::Node jsonToYaml(const nlohmann::json& value);

}  // namespace designer
}  // namespace imagenets
