#include <sensor_msgs/CameraInfo.h>

#include "imagenets/block.h"
#include "imagenets/vision/read_camera_info.h"
#include "imagenets/register_block.h"
#include "imagenets/time.h"

namespace imagenets {
namespace blocks {

// Reads a camera model from a standard ROS camera-info file (the YAML written by
// camera_calibration / camera_info_manager, or the INI format), via camera_calibration_parsers.
class CameraInfoFile : public Block {
 public:
  CameraInfoFile() {
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the camera model (K, D, R, P, size, distortion model)");
    addProperty<std::string>("path", "", "camera-info file (.yaml or .ini); relative to the net file").path();
    addProperty<std::string>("frame_id", "camera", "frame_id of the header (the camera's optical frame)");
  }

  void process(Context& ctx) override {
    const auto path = ctx.property<std::string>("path");
    if (path.empty()) throw BlockError("property 'path' is empty");
    sensor_msgs::CameraInfo::Ptr info;
    try {
      info.reset(new sensor_msgs::CameraInfo(readCameraInfo(path)));
    } catch (const std::runtime_error& e) {
      throw BlockError(std::string("property 'path': ") + e.what());
    }
    if (info->width == 0 || info->height == 0) throw BlockError("'" + path + "': image size is 0");
    if (info->K[0] <= 0 || info->K[4] <= 0) throw BlockError("'" + path + "': focal length in K is not positive");
    info->header.stamp = now();
    info->header.frame_id = ctx.property<std::string>("frame_id");
    ctx.output("camera_info", info);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CameraInfoFile, "imagenets/CameraInfoFile", "acquisition",
                         "Reads a camera model from a ROS camera-info YAML file");
