// Writes a port value to a file a person can open: images as PNG, point clouds as PLY, everything
// else as YAML; a feedback trace also as a PNG plot (score over the swept value).
#pragma once

#include <string>

#include "imagenets/port_type.h"

namespace imagenets {
namespace tool {

// Writes `value` as DIR/STEM.png or DIR/STEM.yaml (atomically: temporary file, then rename).
// Returns the path written.
std::string writeValue(const Value& value, const std::string& dir, const std::string& stem);

}  // namespace tool
}  // namespace imagenets
