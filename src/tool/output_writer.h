// Writes a port value to a file a person can open: images as PNG, point clouds as PLY, everything
// else as YAML.
#pragma once

#include <string>

#include "imagenets/port_type.h"

namespace imagenets {
namespace tool {

// Writes `value` as DIR/STEM.png or DIR/STEM.yaml (atomically: temporary file, then rename).
// Returns the path written.
std::string writeValue(const Value& value, const std::string& dir, const std::string& stem);

// Registers a writer for a message type (e.g. a plot of a feedback trace beside its YAML).
using ExtraWriter = std::function<void(const Value&, const std::string& dir, const std::string& stem)>;
void addExtraWriter(const std::string& type, ExtraWriter writer);

}  // namespace tool
}  // namespace imagenets
