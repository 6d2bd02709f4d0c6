// A block's camera model input: the sensor_msgs/CameraInfo on a port as the renderer's camera model.
#pragma once

#include <string>

#include "imagenets/block.h"
#include "imagenets/vision/render.h"

namespace imagenets {
namespace blocks {

// The camera model of the camera_info on input `port`, for the full image (what its `roi` means
// is the block's business); throws BlockError naming the port when it is missing or unusable.
render::CameraModel inputCameraModel(const Context& ctx, const std::string& port = "camera_info");

}  // namespace blocks
}  // namespace imagenets
