#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Pairs an image with its camera model the ROS way: the camera_info gets the image's header
// (stamp and frame), after checking the model fits the image.
class PairCameraInfo : public Block {
 public:
  PairCameraInfo() {
    addInput<sensor_msgs::Image>("image", "any image");
    addInput<sensor_msgs::CameraInfo>("camera_info", "model of the camera that took it (same size)");
    addOutput<sensor_msgs::Image>("image", "the image, unchanged (same message)");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the model with the image's header");
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat image = inputImage(ctx, "image", {}, nullptr, &header);
    auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
    if (!info) throw BlockError("input 'camera_info': missing");
    if (info->width != static_cast<unsigned>(image.cols) || info->height != static_cast<unsigned>(image.rows)) {
      throw BlockError("input 'camera_info' is for " + std::to_string(info->width) + "x" + std::to_string(info->height) +
                       " images, input 'image' is " + std::to_string(image.cols) + "x" + std::to_string(image.rows));
    }
    sensor_msgs::CameraInfo::Ptr paired(new sensor_msgs::CameraInfo(*info));
    paired->header = header;
    ctx.setOutput("image", ctx.inputValue("image"));
    ctx.output("camera_info", paired);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::PairCameraInfo, "imagenets/PairCameraInfo", "acquisition",
                         "Pairs an image with its camera_info (same header, size checked)");
