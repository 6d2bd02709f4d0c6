#include "imagenets/property.h"

#include <cmath>
#include <regex>
#include <sstream>

#include <boost/filesystem.hpp>
#include <ros/package.h>
#include <yaml-cpp/yaml.h>

namespace imagenets {

const char* kindName(PropertyKind kind) {
  switch (kind) {
    case PropertyKind::Bool: return "bool";
    case PropertyKind::Int: return "int";
    case PropertyKind::Double: return "double";
    case PropertyKind::String: return "string";
    case PropertyKind::Enum: return "enum";
    case PropertyKind::DoubleList: return "double list";
  }
  return "?";
}

PropertySpec::PropertySpec(std::string name, PropertyKind kind, PropertyValue default_value, std::string doc)
    : name_(std::move(name)), kind_(kind), default_(std::move(default_value)), doc_(std::move(doc)) {}

PropertySpec& PropertySpec::range(double min, double max) {
  min_ = min;
  max_ = max;
  return *this;
}

PropertySpec& PropertySpec::choices(std::vector<std::string> allowed) {
  kind_ = PropertyKind::Enum;
  choices_ = std::move(allowed);
  return *this;
}

PropertySpec& PropertySpec::path() {
  is_path_ = true;
  return *this;
}

PropertySpec& PropertySpec::fixedAtLoad() {
  fixed_at_load_ = true;
  return *this;
}

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

bool parseBool(const std::string& s, bool& out) {
  if (s == "true" || s == "True" || s == "TRUE" || s == "1" || s == "yes") return out = true, true;
  if (s == "false" || s == "False" || s == "FALSE" || s == "0" || s == "no") return out = false, true;
  return false;
}

bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end && *end == '\0';
}

bool parseInt(const std::string& s, int& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  long v = std::strtol(s.c_str(), &end, 10);
  if (!end || *end != '\0' || v < INT32_MIN || v > INT32_MAX) return false;
  out = static_cast<int>(v);
  return true;
}

}  // namespace

const PropertySpec& findPropertySpec(const std::vector<const PropertySpec*>& specs, const std::string& name) {
  std::string known;
  for (const PropertySpec* s : specs) {
    if (s->name() == name) return *s;
    known += (known.empty() ? "" : ", ") + s->name();
  }
  throw PropertyError("unknown property '" + name + "' (known: " + (known.empty() ? "none" : known) + ")");
}

PropertyValue parseNamedProperty(const std::vector<const PropertySpec*>& specs, const std::string& name,
                                 const std::string& text, const std::string& base_dir) {
  const PropertySpec& spec = findPropertySpec(specs, name);
  try {
    return spec.parse(text, base_dir);
  } catch (const std::exception& e) {
    throw PropertyError("property '" + name + "': " + e.what());
  }
}

std::string resolvePath(const std::string& path, const std::string& base_dir) {
  std::string out = path;
  static const std::regex find_re(R"(\$\(find ([A-Za-z0-9_]+)\))");
  std::smatch m;
  while (std::regex_search(out, m, find_re)) {
    std::string pkg_path = ros::package::getPath(m[1].str());
    if (pkg_path.empty()) throw PropertyError("$(find " + m[1].str() + "): ROS package not found");
    out = m.prefix().str() + pkg_path + m.suffix().str();
  }
  if (out.empty() || out[0] == '/' || base_dir.empty()) return out;
  return (boost::filesystem::path(base_dir) / out).lexically_normal().string();
}

PropertyValue PropertySpec::parse(const std::string& raw, const std::string& base_dir) const {
  // Strings are taken as written (a sub-net's inline YAML is a string, not a map to parse); a path
  // has `$(find pkg)` expanded and, when relative, is taken relative to base_dir.
  if (kind_ == PropertyKind::String || kind_ == PropertyKind::Enum) {
    return validate(is_path_ ? resolvePath(raw, base_dir) : raw);
  }
  std::string text = raw;
  YAML::Node node;
  try {
    node = YAML::Load(raw);
  } catch (const YAML::Exception& e) {
    throw PropertyError("value " + quote(raw) + " is not valid YAML: " + e.msg);
  }
  if (kind_ == PropertyKind::DoubleList) {
    if (!node.IsSequence()) {
      throw PropertyError("expected a list of numbers like [1, 2.5], got " + quote(raw));
    }
    std::vector<double> list;
    for (const auto& item : node) {
      double d;
      if (!item.IsScalar() || !parseDouble(item.Scalar(), d)) {
        throw PropertyError("expected a list of numbers, got " + quote(raw));
      }
      list.push_back(d);
    }
    return validate(list);
  }
  if (node.IsScalar()) {
    text = node.Scalar();
  } else if (node.IsNull()) {
    text.clear();
  } else {
    throw PropertyError("expected a single " + std::string(kindName(kind_)) + ", got " + quote(raw));
  }
  switch (kind_) {
    case PropertyKind::Bool: {
      bool b;
      if (!parseBool(text, b)) throw PropertyError("expected bool (true/false), got " + quote(raw));
      return validate(b);
    }
    case PropertyKind::Int: {
      int i;
      if (!parseInt(text, i)) throw PropertyError("expected int, got " + quote(raw));
      return validate(i);
    }
    case PropertyKind::Double: {
      double d;
      if (!parseDouble(text, d)) throw PropertyError("expected double, got " + quote(raw));
      return validate(d);
    }
    case PropertyKind::String:
    case PropertyKind::Enum:
    case PropertyKind::DoubleList:
      break;
  }
  throw PropertyError("unsupported property kind");
}

PropertyValue PropertySpec::validate(const PropertyValue& value) const {
  auto wrong = [&] {
    return PropertyError("expected " + std::string(kindName(kind_)) + ", got " + quote(toString(value)));
  };
  auto checkRange = [&](double v) {
    if (!std::isfinite(v)) throw PropertyError("value " + toString(value) + " is not a finite number");
    if ((min_ && v < *min_) || (max_ && v > *max_)) {
      std::ostringstream os;
      os << "value " << toString(value) << " is out of range ["
         << (min_ ? toString(*min_) : std::string("-inf")) << ", "
         << (max_ ? toString(*max_) : std::string("inf")) << "]";
      throw PropertyError(os.str());
    }
  };
  switch (kind_) {
    case PropertyKind::Bool:
      if (!std::holds_alternative<bool>(value)) throw wrong();
      return value;
    case PropertyKind::Int:
      if (!std::holds_alternative<int>(value)) throw wrong();
      checkRange(std::get<int>(value));
      return value;
    case PropertyKind::Double: {
      double d;
      if (std::holds_alternative<double>(value)) d = std::get<double>(value);
      else if (std::holds_alternative<int>(value)) d = std::get<int>(value);
      else throw wrong();
      checkRange(d);
      return d;
    }
    case PropertyKind::String:
      if (!std::holds_alternative<std::string>(value)) throw wrong();
      return value;
    case PropertyKind::Enum: {
      if (!std::holds_alternative<std::string>(value)) throw wrong();
      const std::string& s = std::get<std::string>(value);
      for (const auto& c : choices_) {
        if (c == s) return value;
      }
      std::string list;
      for (const auto& c : choices_) list += (list.empty() ? "" : ", ") + c;
      throw PropertyError("value " + quote(s) + " is not one of: " + list);
    }
    case PropertyKind::DoubleList: {
      if (!std::holds_alternative<std::vector<double>>(value)) throw wrong();
      for (double v : std::get<std::vector<double>>(value)) checkRange(v);
      return value;
    }
  }
  throw wrong();
}

PropertyValue PropertySpec::fromNumber(double number) const {
  if (kind_ == PropertyKind::Int) return validate(static_cast<int>(std::lround(number)));
  if (kind_ == PropertyKind::Double) return validate(number);
  throw PropertyError("property '" + name_ + "' is " + kindName(kind_) + ", not numeric");
}

std::string toString(const PropertyValue& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(int i) const { return std::to_string(i); }
    std::string operator()(double d) const {
      std::ostringstream os;
      os.precision(12);
      os << d;
      return os.str();
    }
    std::string operator()(const std::string& s) const { return s; }
    std::string operator()(const std::vector<double>& v) const {
      std::string out = "[";
      for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + (*this)(v[i]);
      return out + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

double toNumber(const PropertyValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? 1.0 : 0.0;
  if (const int* i = std::get_if<int>(&value)) return *i;
  if (const double* d = std::get_if<double>(&value)) return *d;
  throw PropertyError("value '" + toString(value) + "' is not a number");
}

}  // namespace imagenets
