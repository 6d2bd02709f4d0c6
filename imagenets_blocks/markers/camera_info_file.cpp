// A camera model from a calibration file (camera_calibration_parsers: ROS YAML or INI).
#include <boost/filesystem.hpp>
#include <camera_calibration_parsers/parse.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/registry.h"
#include "imagenets/time.h"

namespace imagenets {
namespace blocks {

class CameraInfoFile : public Block {
 public:
  CameraInfoFile() {
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the camera model read from `path`");
    addProperty("path", "", "camera calibration file (ROS camera_info YAML or INI); relative to the net file").path();
    addProperty("frame_id", "camera", "frame_id of the camera_info header (the camera's optical frame)");
  }

  void process(Context& ctx) override {
    const auto path = ctx.property<std::string>("path");
    if (path.empty()) throw BlockError("property 'path' is empty");
    if (!boost::filesystem::exists(path)) throw BlockError("property 'path': no such file '" + path + "'");
    auto info = boost::make_shared<sensor_msgs::CameraInfo>();
    std::string name;
    if (!camera_calibration_parsers::readCalibration(path, name, *info)) {
      throw BlockError("property 'path': '" + path + "' is not a camera calibration file");
    }
    info->header.stamp = now();
    info->header.frame_id = ctx.property<std::string>("frame_id");
    ctx.output("camera_info", info);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CameraInfoFile, "imagenets/CameraInfoFile", "acquisition",
                         "Reads a camera calibration file (camera_info)");
