// Paper 4.3 / Fig. 4.4: the current extrinsic matrix of a camera is a TF lookup. The head's chain
// hangs from the calibrated PTH fixed point (published by the calibration node), so
// base_link -> calibrated/stereo_left_optical_frame at the image's stamp is the left camera's
// extrinsics at whatever pan/tilt the head had when the image was taken.
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2_ros/buffer.h>

#include "imagenets/register_block.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {

class LookupTransform : public Block {
 public:
  LookupTransform() {
    addOptionalInput<sensor_msgs::CameraInfo>(
        "camera_info", "look up at its header stamp (the image's time); without it, the latest transform");
    addOutput<geometry_msgs::TransformStamped>(
        "transform", "pose of source_frame in target_frame (header.frame_id = target, child_frame_id = source)");
    addProperty<std::string>("target_frame", "base_link", "frame the result is expressed in (e.g. the robot base)");
    addProperty<std::string>("source_frame", "calibrated/stereo_left_optical_frame",
                             "frame whose pose is looked up (e.g. the calibrated camera)");
    addProperty<double>("timeout", 1.0, "seconds to wait for the transform to become available").range(0.0, 600.0);
  }

  // TF is listened to from load time on, so the history covers images taken after the net was
  // loaded (a one-shot `imagenets run` grabs its image after loading). Without a master the
  // lookup reports it when the block runs.
  void configure() override {
    try {
      hardware::ensureRosNode();
      hardware::tfBuffer();
    } catch (const BlockError&) {
    }
  }

  void process(Context& ctx) override {
    const std::string target = ctx.property<std::string>("target_frame");
    const std::string source = ctx.property<std::string>("source_frame");
    if (target.empty()) throw BlockError("property 'target_frame' is empty");
    if (source.empty()) throw BlockError("property 'source_frame' is empty");
    ros::Time stamp(0);  // 0 = the latest common time
    if (auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info")) stamp = info->header.stamp;
    hardware::ensureRosNode();
    auto out = boost::make_shared<geometry_msgs::TransformStamped>(
        hardware::lookupTransform(hardware::tfBuffer(), target, source, stamp, ctx.property<double>("timeout")));
    ctx.output("transform", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::LookupTransform, "imagenets/LookupTransform", "hardware",
                         "Pose of one TF frame in another at a camera_info's stamp (e.g. the current extrinsics)");
