// Moves FRIEND's arm to a configuration through its imagenets/MoveJoints action server.
#include <sensor_msgs/JointState.h>

#include "imagenets/registry.h"
#include "ros_access.h"

namespace imagenets {
namespace blocks {

class MoveArm : public Block {
 public:
  MoveArm() {
    addInput<sensor_msgs::JointState>("configuration", "target joint names and angles (rad)");
    addOutput<sensor_msgs::JointState>("reached", "joint angles reached, stamped when the motion ended");
    addProperty<std::string>("action", "arm/move_joints", "MoveJoints action server of the arm");
    addProperty<double>("speed_scale", 1.0, "fraction of the joints' maximum velocity").range(0.01, 1.0);
    addProperty<double>("server_timeout", 5.0, "seconds to wait for the action server").range(0.0, 600.0);
    addProperty<double>("motion_timeout", 120.0, "seconds to wait for the motion to finish").range(0.1, 3600.0);
  }

  void process(Context& ctx) override {
    const auto target = ctx.input<sensor_msgs::JointState>("configuration");
    if (target->name.size() != target->position.size()) {
      throw BlockError("input 'configuration': " + std::to_string(target->name.size()) + " names but " +
                       std::to_string(target->position.size()) + " positions");
    }
    ctx.output("reached", hardware::moveJoints(ctx.property<std::string>("action"), *target,
                                               ctx.property<double>("speed_scale"), ctx.property<double>("server_timeout"),
                                               ctx.property<double>("motion_timeout")));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::MoveArm, "imagenets/MoveArm", "hardware",
                         "Moves the arm to a joint configuration (actionlib MoveJoints)");
