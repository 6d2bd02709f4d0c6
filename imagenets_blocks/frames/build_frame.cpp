#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/Vector3Stamped.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Builds a frame from a translation and a rotation (e.g. the per-axis median translation and
// the mean rotation of a set of measurements).
class BuildFrame : public Block {
 public:
  BuildFrame() {
    addInput<geometry_msgs::Vector3Stamped>("translation", "origin of the child in the parent frame (m)");
    addInput<geometry_msgs::QuaternionStamped>("rotation", "rotation parent -> child");
    addOutput<geometry_msgs::TransformStamped>("frame", "parent -> child");
    addProperty<std::string>("frame_id", "", "parent frame; empty: the translation's header frame_id");
    addProperty<std::string>("child_frame_id", "child", "child frame id of the result");
  }

  void process(Context& ctx) override {
    auto translation = ctx.input<geometry_msgs::Vector3Stamped>("translation");
    auto rotation = ctx.input<geometry_msgs::QuaternionStamped>("rotation");
    if (!translation) throw BlockError("input 'translation': no value");
    if (!rotation) throw BlockError("input 'rotation': no value");
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    try {
      t.translation() = frames::toVector(translation->vector, "input 'translation'");
      t.linear() = frames::toQuaternion(rotation->quaternion, "input 'rotation'").toRotationMatrix();
    } catch (const frames::FrameError& e) {
      throw BlockError(e.what());
    }
    const auto parent = ctx.property<std::string>("frame_id");
    if (!translation->header.frame_id.empty() && !rotation->header.frame_id.empty() &&
        translation->header.frame_id != rotation->header.frame_id) {
      throw BlockError("input 'translation' is in frame '" + translation->header.frame_id + "' but input 'rotation' in '" +
                       rotation->header.frame_id + "'");
    }
    std_msgs::Header header = translation->header;
    header.stamp = std::max(translation->header.stamp, rotation->header.stamp);
    if (!parent.empty()) header.frame_id = parent;
    ctx.output("frame", frameMsg(t, header, ctx.property<std::string>("child_frame_id")));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::BuildFrame, "imagenets/BuildFrame", "frames",
                         "Builds a frame from translation and rotation");
