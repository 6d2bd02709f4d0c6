#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Chains two frames: out = a * b (parent of a -> child of b), e.g. robot->camera and
// camera->marker give robot->marker.
class ComposeFrames : public Block {
 public:
  ComposeFrames() {
    addInput<geometry_msgs::TransformStamped>("a", "parent -> middle frame");
    addInput<geometry_msgs::TransformStamped>("b", "middle -> child frame");
    addOutput<geometry_msgs::TransformStamped>("frame", "a * b: a's parent -> b's child; stamp of the later input");
    addProperty<bool>("check_frames", true,
                      "require a.child_frame_id == b.header.frame_id (when both are set)");
  }

  void process(Context& ctx) override {
    geometry_msgs::TransformStamped::ConstPtr a_msg, b_msg;
    const Eigen::Isometry3d a = inputFrame(ctx, "a", &a_msg);
    const Eigen::Isometry3d b = inputFrame(ctx, "b", &b_msg);
    if (ctx.property<bool>("check_frames") && !a_msg->child_frame_id.empty() && !b_msg->header.frame_id.empty() &&
        a_msg->child_frame_id != b_msg->header.frame_id) {
      throw BlockError("frames do not chain: input 'a' ends in '" + a_msg->child_frame_id + "' but input 'b' starts in '" +
                       b_msg->header.frame_id + "'");
    }
    std_msgs::Header header = a_msg->header;
    header.stamp = std::max(a_msg->header.stamp, b_msg->header.stamp);
    ctx.output("frame", frameMsg(a * b, header, b_msg->child_frame_id));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ComposeFrames, "imagenets/ComposeFrames", "frames",
                         "Chains two frames (a * b)");
