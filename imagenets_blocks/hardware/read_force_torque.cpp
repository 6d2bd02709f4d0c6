// Reads the wrist force-torque sensor (the next geometry_msgs/WrenchStamped message).
#include <geometry_msgs/WrenchStamped.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/register_block.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {

class ReadForceTorque : public Block {
 public:
  ReadForceTorque() {
    addOptionalInput<sensor_msgs::JointState>("after", "read only after this (e.g. MoveArm.reached): orders the net");
    addOutput<geometry_msgs::WrenchStamped>("wrench", "force (N) and torque (N m) in the sensor frame");
    addProperty<std::string>("topic", "ft_sensor/wrench", "WrenchStamped topic of the sensor");
    addProperty<double>("timeout", 2.0, "seconds to wait for a message").range(0.01, 600.0);
  }
  void process(Context& ctx) override {
    ctx.output("wrench", hardware::waitForMessage<geometry_msgs::WrenchStamped>(ctx.property<std::string>("topic"),
                                                                                ctx.property<double>("timeout")));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ReadForceTorque, "imagenets/ReadForceTorque", "hardware",
                         "The wrist force-torque sensor's current wrench");
