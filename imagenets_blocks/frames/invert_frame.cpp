#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Inverts a frame: parent -> child becomes child -> parent (frame ids swapped).
class InvertFrame : public Block {
 public:
  InvertFrame() {
    addInput<geometry_msgs::TransformStamped>("frame", "parent -> child");
    addOutput<geometry_msgs::TransformStamped>("frame", "child -> parent");
  }

  void process(Context& ctx) override {
    geometry_msgs::TransformStamped::ConstPtr msg;
    const Eigen::Isometry3d t = inputFrame(ctx, "frame", &msg);
    std_msgs::Header header = msg->header;
    header.frame_id = msg->child_frame_id;
    ctx.output("frame", frameMsg(t.inverse(), header, msg->header.frame_id));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::InvertFrame, "imagenets/InvertFrame", "frames", "Inverts a frame");
