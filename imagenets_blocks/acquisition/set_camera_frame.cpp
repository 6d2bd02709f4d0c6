// Re-labels an image + camera_info pair into another frame (paper 4.3, Fig. 4.4): the driver stamps
// its images with the camera frame of the robot model it knows, while the calibrated camera is
// another TF frame (calibrated/stereo_left_optical_frame). Downstream consumers that place data by
// header.frame_id — stereo_image_proc's point cloud, rviz — then put it where the calibration says.
#include <algorithm>

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

class SetCameraFrame : public Block {
 public:
  SetCameraFrame() {
    addInput<sensor_msgs::Image>("image", "any image");
    addInput<sensor_msgs::CameraInfo>("camera_info", "its camera model (same stamp)");
    addOutput<sensor_msgs::Image>("image", "the image with header.frame_id = frame_id (a copy: messages are immutable)");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the camera model with header.frame_id = frame_id");
    addProperty<std::string>("frame_id", "calibrated/stereo_left_optical_frame", "the new frame of both messages");
  }

  void process(Context& ctx) override {
    const std::string frame = ctx.property<std::string>("frame_id");
    if (frame.empty()) throw BlockError("property 'frame_id' is empty");
    if (frame.find_first_of(" \t\n") != std::string::npos) {
      throw BlockError("property 'frame_id': '" + frame + "' contains white space");
    }
    auto image = ctx.input<sensor_msgs::Image>("image");
    auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
    if (!image) throw BlockError("input 'image': missing");
    if (!info) throw BlockError("input 'camera_info': missing");
    if (image->header.stamp != info->header.stamp) {
      throw BlockError("input 'camera_info' (stamp " + std::to_string(info->header.stamp.toSec()) +
                       ") is not the model of input 'image' (stamp " + std::to_string(image->header.stamp.toSec()) + ")");
    }
    // camera_info keeps the sensor's full size; a decimated or cropped image says so in
    // binning_x/y and roi (image_proc/crop_decimate).
    const unsigned bx = std::max(1u, info->binning_x), by = std::max(1u, info->binning_y);
    const unsigned w = (info->roi.width ? info->roi.width : info->width) / bx;
    const unsigned h = (info->roi.height ? info->roi.height : info->height) / by;
    if (w != image->width || h != image->height) {
      throw BlockError("input 'camera_info' is for " + std::to_string(w) + "x" + std::to_string(h) +
                       " images (size, roi, binning), input 'image' is " + std::to_string(image->width) + "x" +
                       std::to_string(image->height));
    }
    auto relabelled_image = boost::make_shared<sensor_msgs::Image>(*image);
    relabelled_image->header.frame_id = frame;
    auto relabelled_info = boost::make_shared<sensor_msgs::CameraInfo>(*info);
    relabelled_info->header.frame_id = frame;
    ctx.output("image", relabelled_image);
    ctx.output("camera_info", relabelled_info);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SetCameraFrame, "imagenets/SetCameraFrame", "acquisition",
                         "Re-labels an image + camera_info pair into another frame (e.g. the calibrated camera)");
