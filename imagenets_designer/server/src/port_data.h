// Port values as the binary WebSocket frames of the Designer protocol (designer/PROTOCOL.md):
// 4-byte little-endian header length, the JSON header, the payload. Images: a JPEG thumbnail
// (preview) or the raw pixels (full); point clouds: float32 xyz + uint8 rgb + pad per point;
// everything else: the value as JSON.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "imagenets/port_type.h"

namespace imagenets {
namespace designer {

constexpr int kPreviewWidth = 256;

// `header` gets port/mode/revision from the caller; an empty value gives format "none".
std::string encodePortFrame(const Value& value, const std::string& mode, nlohmann::json header);

// Any message as JSON: frames and poses as {frame_id, child_frame_id, xyz, rpy, q}, everything
// else as the dump of its fields.
nlohmann::json messageToJson(const Value& value);

// ROS's message printer output ("name: value", "name[]" + "  name[i]: ...") as JSON.
nlohmann::json printedMessageToJson(const std::string& printed);

// Splits a frame back into header and payload (tests, benchmark, clients written in C++).
bool decodePortFrame(const std::string& frame, nlohmann::json& header, std::string& payload);

}  // namespace designer
}  // namespace imagenets
