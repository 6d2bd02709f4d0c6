#include "move_joint_group.h"

#include "ros_access.h"

namespace imagenets {
namespace blocks {

MoveJointGroup::MoveJointGroup(const std::string& target_doc, const std::string& default_action,
                               const std::string& action_doc, double default_motion_timeout) {
  addInput<sensor_msgs::JointState>("configuration", target_doc);
  addOutput<sensor_msgs::JointState>("reached", "joint angles reached, stamped when the motion ended");
  addProperty<std::string>("action", default_action, action_doc);
  addProperty<double>("speed_scale", 1.0, "fraction of the joints' maximum velocity").range(0.01, 1.0);
  addProperty<double>("server_timeout", 5.0, "seconds to wait for the action server").range(0.0, 600.0);
  addProperty<double>("motion_timeout", default_motion_timeout, "seconds to wait for the motion to finish")
      .range(0.1, 3600.0);
}

void MoveJointGroup::process(Context& ctx) {
  const auto target = ctx.input<sensor_msgs::JointState>("configuration");
  if (target->name.size() != target->position.size()) {
    throw BlockError("input 'configuration': " + std::to_string(target->name.size()) + " names but " +
                     std::to_string(target->position.size()) + " positions");
  }
  ctx.output("reached", hardware::moveJoints(ctx.property<std::string>("action"), *target,
                                             ctx.property<double>("speed_scale"), ctx.property<double>("server_timeout"),
                                             ctx.property<double>("motion_timeout")));
}

}  // namespace blocks
}  // namespace imagenets
