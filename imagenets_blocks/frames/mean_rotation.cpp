#include <geometry_msgs/QuaternionStamped.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Mean rotation of a set of poses by the quaternion eigenvector method (sign-independent; not
// a component mean). Translations are ignored.
class MeanRotation : public Block {
 public:
  MeanRotation() {
    addInput<geometry_msgs::PoseArray>("poses", "the set; every orientation must be a unit quaternion");
    addOutput<geometry_msgs::QuaternionStamped>("rotation", "mean rotation (w >= 0), header of the set");
  }

  void process(Context& ctx) override {
    geometry_msgs::PoseArray::ConstPtr msg;
    std::vector<Eigen::Quaterniond> rotations;
    for (const auto& p : inputPoses(ctx, "poses", &msg)) rotations.emplace_back(p.rotation());
    geometry_msgs::QuaternionStamped::Ptr out(new geometry_msgs::QuaternionStamped);
    out->header = msg->header;
    out->quaternion = frames::toQuaternionMsg(frames::meanRotation(rotations));
    ctx.output("rotation", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::MeanRotation, "imagenets/MeanRotation", "frames",
                         "Mean rotation of a pose set (quaternion eigenvector method)");
