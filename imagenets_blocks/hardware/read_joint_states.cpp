// Reads the robot's current joint angles (the next sensor_msgs/JointState message).
#include <sensor_msgs/JointState.h>

#include "imagenets/register_block.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {

class ReadJointStates : public Block {
 public:
  ReadJointStates() {
    addOptionalInput<sensor_msgs::JointState>("after", "read only after this (e.g. MoveArm.reached): orders the net");
    addOutput<sensor_msgs::JointState>("joint_states", "current joint names, angles (rad) and velocities");
    addProperty<std::string>("topic", "joint_states", "JointState topic");
    addProperty<double>("timeout", 2.0, "seconds to wait for a message").range(0.01, 600.0);
  }
  void process(Context& ctx) override {
    ctx.output("joint_states", hardware::waitForMessage<sensor_msgs::JointState>(ctx.property<std::string>("topic"),
                                                                                 ctx.property<double>("timeout")));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ReadJointStates, "imagenets/ReadJointStates", "hardware",
                         "The robot's current joint angles (next joint_states message)");
