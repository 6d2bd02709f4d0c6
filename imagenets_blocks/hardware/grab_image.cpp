// Grabs one camera's image with its camera_info (identical stamps) taken after the robot has
// settled, as GrabStereoPair grabs a pair (settled_grab.h): e.g. a head's mono camera, which a
// calibration measures with alone.
#include <sensor_msgs/JointState.h>

#include "imagenets/register_block.h"
#include "settled_grab.h"

namespace imagenets {
namespace blocks {

class GrabImage : public Block {
 public:
  GrabImage() {
    addOptionalInput<sensor_msgs::JointState>("after", "grab only after this (e.g. MoveHead.reached): orders the net");
    addOutput<sensor_msgs::Image>("image", "image_raw");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "camera_info, same stamp");
    for (const auto& p : hardware::settledGrabProperties("camera", "camera namespace: NS/{image_raw,camera_info}"))
      addPropertySpec(p);
  }

  void process(Context& ctx) override {
    const auto grabbed = hardware::grabSettled(ctx, {""});
    ctx.output("image", grabbed[0].image);
    ctx.output("camera_info", grabbed[0].info);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::GrabImage, "imagenets/GrabImage", "hardware",
                         "One camera's image + camera_info taken after the robot has settled");
