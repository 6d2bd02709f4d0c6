#include "reconfigure.h"

#include <climits>
#include <cmath>
#include <limits>

namespace imagenets {
namespace {

const char* reconfigureType(PropertyKind kind) {
  switch (kind) {
    case PropertyKind::Bool: return "bool";
    case PropertyKind::Int: return "int";
    case PropertyKind::Double: return "double";
    default: return "str";
  }
}

// A Python string literal (the client evaluates edit_method).
std::string pyQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\\' || c == '\'') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "'";
}

std::string enumEditMethod(const PropertySpec& spec) {
  std::string out = "{'enum': [";
  for (size_t i = 0; i < spec.allowedChoices().size(); ++i) {
    const std::string& c = spec.allowedChoices()[i];
    out += (i ? ", " : "") + std::string("{'name': ") + pyQuote(c) + ", 'type': 'str', 'value': " + pyQuote(c) +
           ", 'description': " + pyQuote(c) + ", 'srcline': 0, 'srcfile': '', 'cconsttype': 'const char * const'," +
           " 'ctype': 'std::string'}";
  }
  return out + "], 'enum_description': " + pyQuote(spec.doc()) + "}";
}

void put(dynamic_reconfigure::Config& config, const PropertySpec& spec, const PropertyValue& value) {
  switch (spec.kind()) {
    case PropertyKind::Bool: {
      dynamic_reconfigure::BoolParameter p;
      p.name = spec.name();
      p.value = std::get<bool>(value);
      config.bools.push_back(p);
      break;
    }
    case PropertyKind::Int: {
      dynamic_reconfigure::IntParameter p;
      p.name = spec.name();
      p.value = std::get<int>(value);
      config.ints.push_back(p);
      break;
    }
    case PropertyKind::Double: {
      dynamic_reconfigure::DoubleParameter p;
      p.name = spec.name();
      p.value = std::holds_alternative<double>(value) ? std::get<double>(value) : toNumber(value);
      config.doubles.push_back(p);
      break;
    }
    default: {
      dynamic_reconfigure::StrParameter p;
      p.name = spec.name();
      p.value = std::holds_alternative<std::string>(value) ? std::get<std::string>(value) : toString(value);
      config.strs.push_back(p);
      break;
    }
  }
}

dynamic_reconfigure::GroupState defaultGroupState() {
  dynamic_reconfigure::GroupState g;
  g.name = "Default";
  g.state = true;
  g.id = 0;
  g.parent = 0;
  return g;
}

// Bounds as the protocol wants them: the declared range, else the type's extremes.
void putBound(dynamic_reconfigure::Config& config, const PropertySpec& spec, bool upper) {
  const std::optional<double>& bound = upper ? spec.max() : spec.min();
  switch (spec.kind()) {
    case PropertyKind::Bool:
      put(config, spec, PropertyValue(upper));
      break;
    case PropertyKind::Int: {
      double b = bound ? *bound : (upper ? INT_MAX : INT_MIN);
      b = std::max<double>(INT_MIN, std::min<double>(INT_MAX, b));
      put(config, spec, PropertyValue(static_cast<int>(upper ? std::floor(b) : std::ceil(b))));
      break;
    }
    case PropertyKind::Double: {
      double inf = std::numeric_limits<double>::infinity();
      put(config, spec, PropertyValue(bound ? *bound : (upper ? inf : -inf)));
      break;
    }
    default:
      put(config, spec, PropertyValue(std::string()));
      break;
  }
}

}  // namespace

dynamic_reconfigure::ConfigDescription describeProperties(const std::vector<const PropertySpec*>& specs) {
  dynamic_reconfigure::ConfigDescription d;
  dynamic_reconfigure::Group group;
  group.name = "Default";
  group.type = "";
  group.id = 0;
  group.parent = 0;
  for (const PropertySpec* spec : specs) {
    dynamic_reconfigure::ParamDescription p;
    p.name = spec->name();
    p.type = reconfigureType(spec->kind());
    p.level = 0;
    p.description = spec->doc();
    if (spec->kind() == PropertyKind::DoubleList) p.description += " (a list: [1, 2.5])";
    p.edit_method = spec->kind() == PropertyKind::Enum ? enumEditMethod(*spec) : "";
    group.parameters.push_back(p);
    putBound(d.min, *spec, false);
    putBound(d.max, *spec, true);
    put(d.dflt, *spec, spec->defaultValue());
  }
  d.groups.push_back(group);
  d.min.groups.push_back(defaultGroupState());
  d.max.groups.push_back(defaultGroupState());
  d.dflt.groups.push_back(defaultGroupState());
  return d;
}

dynamic_reconfigure::Config encodeProperties(const std::vector<const PropertySpec*>& specs,
                                             const PropertyValues& values) {
  dynamic_reconfigure::Config config;
  for (const PropertySpec* spec : specs) {
    auto it = values.find(spec->name());
    put(config, *spec, it != values.end() ? it->second : spec->defaultValue());
  }
  config.groups.push_back(defaultGroupState());
  return config;
}

std::vector<std::pair<std::string, std::string>> decodeRequest(const dynamic_reconfigure::Config& config) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& p : config.bools) out.emplace_back(p.name, p.value ? "true" : "false");
  for (const auto& p : config.ints) out.emplace_back(p.name, std::to_string(p.value));
  for (const auto& p : config.doubles) out.emplace_back(p.name, toString(PropertyValue(p.value)));
  for (const auto& p : config.strs) out.emplace_back(p.name, p.value);
  return out;
}

}  // namespace imagenets
