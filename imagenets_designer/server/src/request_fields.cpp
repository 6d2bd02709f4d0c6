#include "request_fields.h"

#include <yaml-cpp/yaml.h>

#include "imagenets/net_writer.h"
#include "yaml_json.h"

namespace imagenets {
namespace designer {

using json = nlohmann::json;

const json& field(const json& request, const std::string& name) {
  auto it = request.find(name);
  if (it == request.end()) {
    throw RequestError("request '" + request.value("op", std::string()) + "': missing field '" + name + "'");
  }
  return *it;
}

std::string stringField(const json& request, const std::string& name) {
  const json& v = field(request, name);
  if (!v.is_string()) {
    throw RequestError("request '" + request.value("op", std::string()) + "': field '" + name + "' must be a string");
  }
  return v.get<std::string>();
}

std::array<double, 2> positionOf(const json& v, const std::string& what) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    throw RequestError(what + ": a position is [x, y]");
  }
  return {v[0].get<double>(), v[1].get<double>()};
}

std::string propertyText(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return formatNumber(v.get<double>());
  if (v.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + propertyText(v[i]);
    return out + "]";
  }
  throw RequestError("a property value is text, a number, a boolean or a list of numbers");
}

std::vector<PropertySetting> propertySettings(const json& item, const SourceLocation& loc) {
  std::vector<PropertySetting> out;
  auto it = item.find("properties");
  if (it == item.end() || it->is_null()) return out;
  if (!it->is_object()) throw RequestError("'properties' must be {name: text}");
  for (auto p = it->begin(); p != it->end(); ++p) out.push_back(PropertySetting{p.key(), propertyText(p.value()), loc});
  return out;
}

FeedbackSpec feedbackOf(const BlockSpec& block, const json& feedback, const NetSpec& spec) {
  if (!feedback.is_object()) throw RequestError("block '" + block.name + "': feedback must be an object or null");
  // Written into a one-block net and read back.
  YAML::Node root;
  root["blocks"][block.name]["type"] = block.type;
  root["blocks"][block.name]["feedback"] = jsonToYaml(feedback);
  YAML::Emitter e;
  e << root;
  NetSpec parsed = parseNetText(e.c_str(), spec.origin, spec.base_dir);
  return *parsed.blocks.front().feedback;
}

}  // namespace designer
}  // namespace imagenets
