#include "robot_description/yaml_fields.h"

namespace robot_description {
namespace yaml_fields {

std::runtime_error error(const std::string& where, const std::string& what) {
  return std::runtime_error(where + ": " + what);
}

YAML::Node need(const YAML::Node& node, const std::string& key, const std::string& where) {
  if (!node.IsMap() || !node[key]) throw error(where, "missing key '" + key + "'");
  return node[key];
}

double number(const YAML::Node& node, const std::string& key, const std::string& where) {
  const YAML::Node v = need(node, key, where);
  try {
    return v.as<double>();
  } catch (const YAML::Exception&) {
    throw error(where + "." + key, "expected a number, got '" + YAML::Dump(v) + "'");
  }
}

double numberOr(const YAML::Node& node, const std::string& key, double fallback, const std::string& where) {
  return node.IsMap() && node[key] ? number(node, key, where) : fallback;
}

std::vector<double> numbers(const YAML::Node& v, const std::string& where, size_t expected_size) {
  if (!v.IsSequence()) throw error(where, "expected a list of numbers");
  std::vector<double> out;
  for (const auto& e : v) {
    try {
      out.push_back(e.as<double>());
    } catch (const YAML::Exception&) {
      throw error(where, "expected a number, got '" + YAML::Dump(e) + "'");
    }
  }
  if (expected_size && out.size() != expected_size) {
    throw error(where, "expected " + std::to_string(expected_size) + " numbers, got " + std::to_string(out.size()));
  }
  return out;
}

Eigen::Vector3d vec3(const YAML::Node& node, const std::string& key, const std::string& where, double scale) {
  if (!node.IsMap() || !node[key]) return Eigen::Vector3d::Zero();
  auto v = numbers(node[key], where + "." + key, 3);
  return Eigen::Vector3d(v[0], v[1], v[2]) * scale;
}

}  // namespace yaml_fields
}  // namespace robot_description
