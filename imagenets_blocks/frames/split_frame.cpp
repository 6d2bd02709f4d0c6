#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/Vector3Stamped.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Splits a frame into its translation and its rotation (both in the parent frame).
class SplitFrame : public Block {
 public:
  SplitFrame() {
    addInput<geometry_msgs::TransformStamped>("frame", "parent -> child");
    addOutput<geometry_msgs::Vector3Stamped>("translation", "origin of the child in the parent frame (m)");
    addOutput<geometry_msgs::QuaternionStamped>("rotation", "rotation parent -> child (unit quaternion)");
  }

  void process(Context& ctx) override {
    geometry_msgs::TransformStamped::ConstPtr msg;
    const Eigen::Isometry3d t = inputFrame(ctx, "frame", &msg);
    geometry_msgs::Vector3Stamped::Ptr translation(new geometry_msgs::Vector3Stamped);
    translation->header = msg->header;
    translation->vector = frames::toVector3Msg(t.translation());
    geometry_msgs::QuaternionStamped::Ptr rotation(new geometry_msgs::QuaternionStamped);
    rotation->header = msg->header;
    rotation->quaternion = frames::toQuaternionMsg(Eigen::Quaterniond(t.rotation()));
    ctx.output("translation", translation);
    ctx.output("rotation", rotation);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SplitFrame, "imagenets/SplitFrame", "frames",
                         "Splits a frame into translation and rotation");
