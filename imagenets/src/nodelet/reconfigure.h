// The dynamic_reconfigure protocol, generated from property declarations instead of a .cfg file:
// the description (types, ranges, defaults, enum choices), the current configuration, and the
// values a Reconfigure request carries. Lists of numbers travel as YAML text ("[1, 2.5]").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>

#include "imagenets/property.h"

namespace imagenets {

dynamic_reconfigure::ConfigDescription describeProperties(const std::vector<const PropertySpec*>& specs);
dynamic_reconfigure::Config encodeProperties(const std::vector<const PropertySpec*>& specs,
                                             const PropertyValues& values);
// The (name, text) pairs of a request; text is what a net file would hold for the value (read it
// with PropertySpec::parse).
std::vector<std::pair<std::string, std::string>> decodeRequest(const dynamic_reconfigure::Config& config);

}  // namespace imagenets
