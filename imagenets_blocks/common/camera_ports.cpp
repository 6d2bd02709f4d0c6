#include "camera_ports.h"

#include <sensor_msgs/CameraInfo.h>

namespace imagenets {
namespace blocks {

render::CameraModel inputCameraModel(const Context& ctx, const std::string& port) {
  const auto info = ctx.input<sensor_msgs::CameraInfo>(port);
  if (!info) throw BlockError("input '" + port + "': missing");
  try {
    return render::CameraModel::fromCameraInfo(*info);
  } catch (const std::exception& e) {
    throw BlockError("input '" + port + "': " + e.what());
  }
}

}  // namespace blocks
}  // namespace imagenets
