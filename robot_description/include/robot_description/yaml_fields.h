// Reading description files (robot, true-robot error) with errors that name the file and the key:
// "robot.yaml: arm.joints[2].alpha_deg: expected a number, got 'x'".
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

namespace robot_description {
namespace yaml_fields {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::runtime_error error(const std::string& where, const std::string& what);
// node[key], or an error naming the missing key.
YAML::Node need(const YAML::Node& node, const std::string& key, const std::string& where);
double number(const YAML::Node& node, const std::string& key, const std::string& where);
double numberOr(const YAML::Node& node, const std::string& key, double fallback, const std::string& where);
// A list of numbers; with expected_size > 0 exactly that many.
std::vector<double> numbers(const YAML::Node& list, const std::string& where, size_t expected_size);
// node[key] as 3 numbers times scale; zero when the key is absent.
Eigen::Vector3d vec3(const YAML::Node& node, const std::string& key, const std::string& where, double scale = 1.0);

}  // namespace yaml_fields
}  // namespace robot_description
