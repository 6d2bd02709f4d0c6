#include <cmath>

#include "frame_ports.h"
#include "imagenets/register_block.h"
#include "imagenets/time.h"

namespace imagenets {
namespace blocks {

// A fixed frame from its properties (a mounting offset, a nominal camera pose, the gripper ->
// marker offset): the net equivalent of a tf2 static transform.
class StaticFrame : public Block {
 public:
  StaticFrame() {
    addOutput<geometry_msgs::TransformStamped>("frame", "frame_id -> child_frame_id");
    addProperty<std::string>("frame_id", "base_link", "parent frame");
    addProperty<std::string>("child_frame_id", "child", "child frame");
    addProperty<std::vector<double>>("xyz", std::vector<double>{0, 0, 0}, "translation x y z (m)");
    addProperty<std::vector<double>>("rpy", std::vector<double>{0, 0, 0},
                                     "rotation roll pitch yaw (rad), fixed axes x-y-z (R = Rz(yaw) Ry(pitch) Rx(roll))");
  }

  void process(Context& ctx) override {
    const auto xyz = ctx.property<std::vector<double>>("xyz"), rpy = ctx.property<std::vector<double>>("rpy");
    if (xyz.size() != 3) throw BlockError("property 'xyz': " + std::to_string(xyz.size()) + " values, expected 3");
    if (rpy.size() != 3) throw BlockError("property 'rpy': " + std::to_string(rpy.size()) + " values, expected 3");
    for (double v : xyz) {
      if (!std::isfinite(v)) throw BlockError("property 'xyz': value not finite");
    }
    for (double v : rpy) {
      if (!std::isfinite(v)) throw BlockError("property 'rpy': value not finite");
    }
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    t.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    std_msgs::Header header;
    header.stamp = now();
    header.frame_id = ctx.property<std::string>("frame_id");
    ctx.output("frame", frameMsg(t, header, ctx.property<std::string>("child_frame_id")));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::StaticFrame, "imagenets/StaticFrame", "frames",
                         "A fixed frame from translation and roll-pitch-yaw properties");
