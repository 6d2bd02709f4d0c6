#include <geometry_msgs/PoseStamped.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// A pose (what detectors output: where an object is in the header's frame) as a frame
// header.frame_id -> child_frame_id, so the frames blocks can chain it. A PoseStamped names no
// child frame: the property gives it.
class PoseToFrame : public Block {
 public:
  PoseToFrame() {
    addInput<geometry_msgs::PoseStamped>("pose", "the object's pose in header.frame_id");
    addOutput<geometry_msgs::TransformStamped>("frame", "frame_id -> child_frame_id, same header stamp");
    addProperty<std::string>("child_frame_id", "object", "child frame of the result (the object the pose is of)");
    addProperty<std::string>("frame_id", "", "parent frame of the result; empty: the pose's header.frame_id");
  }

  void process(Context& ctx) override {
    auto pose = ctx.input<geometry_msgs::PoseStamped>("pose");
    if (!pose) throw BlockError("input 'pose': no pose");
    const std::string child = ctx.property<std::string>("child_frame_id");
    if (child.empty()) throw BlockError("property 'child_frame_id': empty (a frame needs a child frame name)");
    Eigen::Isometry3d t;
    try {
      t = frames::toIsometry(pose->pose, "input 'pose'");
    } catch (const frames::FrameError& e) {
      throw BlockError(e.what());
    }
    std_msgs::Header header = pose->header;
    const std::string parent = ctx.property<std::string>("frame_id");
    if (!parent.empty()) header.frame_id = parent;
    ctx.output("frame", frameMsg(t, header, child));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::PoseToFrame, "imagenets/PoseToFrame", "frames",
                         "A PoseStamped as a frame (TransformStamped) with a named child frame");
