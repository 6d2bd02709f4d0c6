// Grabs one synchronised stereo pair (left/right image + camera_info with identical stamps) taken
// after the robot has settled: it waits until joint_states report no motion for `settle_time`,
// then (optionally) triggers the camera, and takes the first pair stamped after that moment
// (settled_grab.h, as GrabImage for one camera).
#include <sensor_msgs/JointState.h>

#include "imagenets/register_block.h"
#include "settled_grab.h"

namespace imagenets {
namespace blocks {

class GrabStereoPair : public Block {
 public:
  GrabStereoPair() {
    addOptionalInput<sensor_msgs::JointState>("after", "grab only after this (e.g. MoveHead.reached): orders the net");
    addOutput<sensor_msgs::Image>("left_image", "left image_raw");
    addOutput<sensor_msgs::Image>("right_image", "right image_raw, same stamp");
    addOutput<sensor_msgs::CameraInfo>("left_info", "left camera_info, same stamp");
    addOutput<sensor_msgs::CameraInfo>("right_info", "right camera_info, same stamp");
    for (const auto& p : hardware::settledGrabProperties("stereo", "camera namespace: NS/{left,right}/{image_raw,camera_info}"))
      addPropertySpec(p);
  }

  void process(Context& ctx) override {
    const auto pair = hardware::grabSettled(ctx, {"left", "right"});
    ctx.output("left_image", pair[0].image);
    ctx.output("right_image", pair[1].image);
    ctx.output("left_info", pair[0].info);
    ctx.output("right_info", pair[1].info);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::GrabStereoPair, "imagenets/GrabStereoPair", "hardware",
                         "A synchronised stereo pair (images + camera_info) taken after the robot has settled");
