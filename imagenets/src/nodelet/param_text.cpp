#include "imagenets/param_text.h"

#include <cstdio>

#include <yaml-cpp/yaml.h>

namespace imagenets {
namespace {

YAML::Node toYaml(XmlRpc::XmlRpcValue& v) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return YAML::Node(static_cast<bool>(v));
    case XmlRpc::XmlRpcValue::TypeInt: return YAML::Node(static_cast<int>(v));
    case XmlRpc::XmlRpcValue::TypeDouble: {
      char buf[40];
      std::snprintf(buf, sizeof(buf), "%.17g", static_cast<double>(v));
      std::string text = buf;
      // Keep a double a double in the text ("2" would read back as an int).
      if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
      YAML::Node n(text);
      return n;
    }
    case XmlRpc::XmlRpcValue::TypeString: return YAML::Node(static_cast<std::string>(v));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node seq(YAML::NodeType::Sequence);
      for (int i = 0; i < v.size(); ++i) seq.push_back(toYaml(v[i]));
      return seq;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (auto& kv : v) map[kv.first] = toYaml(kv.second);
      return map;
    }
    default: return YAML::Node();
  }
}

void emitFlowSequences(YAML::Emitter& out, const YAML::Node& node) {
  if (node.IsSequence()) {
    out << YAML::Flow << YAML::BeginSeq;
    for (const auto& item : node) emitFlowSequences(out, item);
    out << YAML::EndSeq;
  } else if (node.IsMap()) {
    out << YAML::BeginMap;
    for (const auto& kv : node) {
      out << YAML::Key << kv.first.Scalar() << YAML::Value;
      emitFlowSequences(out, kv.second);
    }
    out << YAML::EndMap;
  } else {
    out << node;
  }
}

}  // namespace

std::string paramToYaml(XmlRpc::XmlRpcValue value) {
  YAML::Emitter out;
  emitFlowSequences(out, toYaml(value));
  return out.c_str();
}

std::string paramText(const XmlRpc::XmlRpcValue& value) {
  // A string is not read as YAML ("a: b" is a fine string).
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    return static_cast<std::string>(const_cast<XmlRpc::XmlRpcValue&>(value));
  }
  return paramToYaml(value);
}

XmlRpc::XmlRpcValue propertyToParam(const PropertyValue& value) {
  struct Visitor {
    XmlRpc::XmlRpcValue operator()(bool b) const { return XmlRpc::XmlRpcValue(b); }
    XmlRpc::XmlRpcValue operator()(int i) const { return XmlRpc::XmlRpcValue(i); }
    XmlRpc::XmlRpcValue operator()(double d) const { return XmlRpc::XmlRpcValue(d); }
    XmlRpc::XmlRpcValue operator()(const std::string& s) const { return XmlRpc::XmlRpcValue(s); }
    XmlRpc::XmlRpcValue operator()(const std::vector<double>& list) const {
      XmlRpc::XmlRpcValue v;
      v.setSize(static_cast<int>(list.size()));
      for (size_t i = 0; i < list.size(); ++i) v[static_cast<int>(i)] = list[i];
      return v;
    }
  };
  return std::visit(Visitor{}, value);
}

}  // namespace imagenets
