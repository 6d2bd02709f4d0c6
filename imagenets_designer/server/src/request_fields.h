// Reading the fields of a protocol request (designer/PROTOCOL.md); a missing or mistyped field is
// a RequestError naming the request and the field.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "imagenets/net.h"
#include "request_error.h"

namespace imagenets {
namespace designer {

const nlohmann::json& field(const nlohmann::json& request, const std::string& name);
std::string stringField(const nlohmann::json& request, const std::string& name);
// [x, y]
std::array<double, 2> positionOf(const nlohmann::json& v, const std::string& what);
// A property value: text as a net file holds it; numbers, booleans and lists are accepted.
std::string propertyText(const nlohmann::json& v);
// The optional `properties: {name: text}` of a block in a request.
std::vector<PropertySetting> propertySettings(const nlohmann::json& item, const SourceLocation& loc);
// A feedback map as the net file writes it, parsed by the engine (one definition of its keys and
// checks) for `block` of `spec`.
FeedbackSpec feedbackOf(const BlockSpec& block, const nlohmann::json& feedback, const NetSpec& spec);

}  // namespace designer
}  // namespace imagenets
