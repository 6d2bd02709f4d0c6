// The JSON shapes of the Designer protocol built from engine objects: the block registry, ports,
// properties, stats, run events and the view of a built net (a sub-net's inner net).
#pragma once

#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "imagenets/executor.h"
#include "net_document.h"

namespace imagenets {
namespace designer {

// A message as sent: JSON text, with invalid UTF-8 (from a file name, a block's error text)
// replaced instead of throwing.
std::string jsonText(const nlohmann::json& message);

nlohmann::json registryJson();
nlohmann::json portJson(const PortSpec& port);
nlohmann::json statsJson(const BlockStats& stats);
nlohmann::json eventJson(const RunEvent& event);
nlohmann::json feedbackJson(const FeedbackSpec& feedback);
nlohmann::json propertyValueJson(const PropertyValue& value);
// A block's ports from its built instance (a sub-net's come from its inner net; feedback adds
// feedback_trace).
void addPorts(nlohmann::json& block, const Block& instance);
// A built net shown read-only (a sub-net's inner net), with the stats of `executor` if given.
nlohmann::json builtNetState(const Net& net, const Executor* executor);
// The edited net's `blocks` and `links` into `state`: as the document has them, with the ports,
// defaults and stats of the executor built from it.
void addDocument(nlohmann::json& state, const NetDocument& doc, const Executor& executor);

}  // namespace designer
}  // namespace imagenets
