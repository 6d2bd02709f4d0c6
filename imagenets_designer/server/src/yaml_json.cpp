#include "yaml_json.h"

#include <cstdlib>

#include "imagenets/net_writer.h"

namespace imagenets {
namespace designer {

nlohmann::json yamlToJson(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      nlohmann::json out = nlohmann::json::object();
      for (const auto& kv : node) out[kv.first.Scalar()] = yamlToJson(kv.second);
      return out;
    }
    case YAML::NodeType::Sequence: {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& item : node) out.push_back(yamlToJson(item));
      return out;
    }
    case YAML::NodeType::Scalar: {
      const std::string& s = node.Scalar();
      if (node.Tag() == "!") return s;  // quoted: a string whatever it looks like
      if (s == "true") return true;
      if (s == "false") return false;
      if (!s.empty()) {
        char* end = nullptr;
        const double d = std::strtod(s.c_str(), &end);
        if (end && *end == '\0') {
          if (s.find_first_of(".eE") == std::string::npos && std::abs(d) < 1e15) return static_cast<long long>(d);
          return d;
        }
      }
      return s;
    }
    default:
      return nullptr;
  }
}

YAML::Node jsonToYaml(const nlohmann::json& value) {
  if (value.is_object()) {
    YAML::Node out(YAML::NodeType::Map);
    for (auto it = value.begin(); it != value.end(); ++it) out[it.key()] = jsonToYaml(it.value());
    return out;
  }
  if (value.is_array()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (const auto& item : value) out.push_back(jsonToYaml(item));
    return out;
  }
  if (value.is_boolean()) return YAML::Node(value.get<bool>() ? "true" : "false");
  if (value.is_number_integer()) return YAML::Node(std::to_string(value.get<long long>()));
  if (value.is_number()) return YAML::Node(formatNumber(value.get<double>()));
  if (value.is_string()) return YAML::Node(value.get<std::string>());
  return YAML::Node();
}

}  // namespace designer
}  // namespace imagenets
