// The head half of the paper's Fig. 3.1: pan and tilt that centre the arm's tool centre point in
// the stereo camera, computed from the NOMINAL kinematics (DH of arm and head). On the real (or
// simulated, deliberately mis-mounted) robot the TCP then lands near, not exactly on, the image
// centre; that residual is what the calibration removes.
#include <cmath>

#include <boost/make_shared.hpp>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/robot.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

class LookAtTcp : public Block {
 public:
  LookAtTcp() {
    addInput<sensor_msgs::JointState>("arm_configuration", "arm joint angles (rad), e.g. MoveArm.reached");
    addOutput<sensor_msgs::JointState>("head_configuration", "pan and tilt (rad) that centre the target");
    addOutput<geometry_msgs::TransformStamped>("target", "the looked-at point (TCP + offset) in the robot base frame");
    addProperty<std::vector<double>>("offset", {0.0, 0.0, 0.0}, "point to look at, in the TCP frame (m)");
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
  }

  void process(Context& ctx) override {
    const auto& d = robotDescription(ctx.property<std::string>("description"));
    const auto arm = ctx.input<sensor_msgs::JointState>("arm_configuration");
    const std::vector<double> q = jointPositions(*arm, d.arm.names(), "arm_configuration");
    const auto offset = ctx.property<std::vector<double>>("offset");
    if (offset.size() != 3) throw BlockError("property 'offset': expected 3 numbers (x y z), got " + std::to_string(offset.size()));
    const robot_description::RobotModel model(d);
    const Eigen::Vector3d target = model.tcp(q) * Eigen::Vector3d(offset[0], offset[1], offset[2]);
    const auto pt = model.lookAt(target, {0.0, 0.5});

    auto head = boost::make_shared<sensor_msgs::JointState>();
    head->header.stamp = arm->header.stamp;
    head->name = d.head.names();
    head->position = {pt[0], pt[1]};
    ctx.output("head_configuration", head);

    auto t = boost::make_shared<geometry_msgs::TransformStamped>();
    t->header.stamp = arm->header.stamp;
    t->header.frame_id = d.base_frame;
    t->child_frame_id = "look_at_target";
    t->transform.translation.x = target.x();
    t->transform.translation.y = target.y();
    t->transform.translation.z = target.z();
    t->transform.rotation.w = 1.0;
    ctx.output("target", t);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::LookAtTcp, "imagenets/LookAtTcp", "hardware",
                         "Pan and tilt that centre the arm's TCP in the stereo camera (nominal kinematics)");
