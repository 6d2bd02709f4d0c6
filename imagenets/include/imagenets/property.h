// Properties: a block's typed, documented parameters (the paper's "properties", e.g. a
// threshold 0..255). Declared once in the block's constructor; values are checked against the
// declaration wherever they come from (net file, rosparam, command line, dynamic_reconfigure).
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace imagenets {

enum class PropertyKind { Bool, Int, Double, String, Enum, DoubleList };
const char* kindName(PropertyKind kind);

using PropertyValue = std::variant<bool, int, double, std::string, std::vector<double>>;

// A value that does not fit a property's declaration. The message says what and why.
struct PropertyError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class PropertySpec {
 public:
  PropertySpec(std::string name, PropertyKind kind, PropertyValue default_value, std::string doc);

  // Builders for the declaration in a block's constructor.
  PropertySpec& range(double min, double max);
  PropertySpec& choices(std::vector<std::string> allowed);  // turns a string into an enumeration
  PropertySpec& path();  // a file path: relative values resolve against the net file's folder
  PropertySpec& fixedAtLoad();  // takes effect at load only: a live change is refused

  const std::string& name() const { return name_; }
  PropertyKind kind() const { return kind_; }
  const PropertyValue& defaultValue() const { return default_; }
  const std::string& doc() const { return doc_; }
  const std::optional<double>& min() const { return min_; }
  const std::optional<double>& max() const { return max_; }
  const std::vector<std::string>& allowedChoices() const { return choices_; }
  bool isPath() const { return is_path_; }
  bool isFixedAtLoad() const { return fixed_at_load_; }
  bool numeric() const { return kind_ == PropertyKind::Int || kind_ == PropertyKind::Double; }

  // The one way a written value (net file, command line, ROS parameter, dynamic_reconfigure)
  // becomes a property value: parses text (a YAML scalar or flow sequence, "72", "true",
  // "[1, 2]"; a string as written) into a valid value; a path gets `$(find pkg)` expanded and,
  // when relative, is taken relative to base_dir (empty: the working directory).
  PropertyValue parse(const std::string& text, const std::string& base_dir = "") const;
  // Checks type, range and choices of a value; throws PropertyError naming the problem.
  PropertyValue validate(const PropertyValue& value) const;
  // Numeric properties also accept a double (feedback sweeps them); ints are rounded.
  PropertyValue fromNumber(double number) const;

 private:
  std::string name_;
  PropertyKind kind_;
  PropertyValue default_;
  std::string doc_;
  std::optional<double> min_, max_;
  std::vector<std::string> choices_;
  bool is_path_ = false;
  bool fixed_at_load_ = false;
};

// The property `name` among `specs`; throws PropertyError "unknown property 'x' (known: a, b)".
const PropertySpec& findPropertySpec(const std::vector<const PropertySpec*>& specs, const std::string& name);
// A written value for the property `name` among `specs` (PropertySpec::parse). Throws PropertyError
// "unknown property 'x' (known: a, b)" or "property 'x': <why>"; the caller adds where (file:line
// and block, ROS parameter, ...).
PropertyValue parseNamedProperty(const std::vector<const PropertySpec*>& specs, const std::string& name,
                                 const std::string& text, const std::string& base_dir = "");

// Resolves `$(find pkg)` and relative paths (against base_dir); throws PropertyError.
std::string resolvePath(const std::string& path, const std::string& base_dir);

std::string toString(const PropertyValue& value);
double toNumber(const PropertyValue& value);  // bool, int, double; throws otherwise

// The current values of one block's properties, by name.
using PropertyValues = std::map<std::string, PropertyValue>;

template <class T>
struct PropertyTraits;
template <>
struct PropertyTraits<bool> {
  static constexpr PropertyKind kind = PropertyKind::Bool;
};
template <>
struct PropertyTraits<int> {
  static constexpr PropertyKind kind = PropertyKind::Int;
};
template <>
struct PropertyTraits<double> {
  static constexpr PropertyKind kind = PropertyKind::Double;
};
template <>
struct PropertyTraits<std::string> {
  static constexpr PropertyKind kind = PropertyKind::String;
};
template <>
struct PropertyTraits<std::vector<double>> {
  static constexpr PropertyKind kind = PropertyKind::DoubleList;
};

}  // namespace imagenets
