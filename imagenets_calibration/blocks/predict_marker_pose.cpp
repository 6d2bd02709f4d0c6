// Where the nominal model expects the gripper marker in each camera (T_camera_marker) at the
// measured joint angles: the detection's region of interest and its pose-ambiguity hint. The
// stereo pair's two, and the head's mono camera's when the description has one.
#include <boost/make_shared.hpp>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/JointState.h>

#include "calibration_ports.h"
#include "imagenets/vision/frames.h"
#include "imagenets/blocks/robot.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class PredictMarkerPose : public imagenets::Block {
 public:
  PredictMarkerPose() {
    addInput<sensor_msgs::JointState>("arm_joints", "arm joint_states");
    addInput<sensor_msgs::JointState>("head_joints", "head joint_states");
    addOutput<geometry_msgs::PoseStamped>("left", "marker in the left optical frame, nominal");
    addOutput<geometry_msgs::PoseStamped>("right", "marker in the right optical frame, nominal");
    addOutput<geometry_msgs::PoseStamped>("mono", "marker in the mono camera's optical frame, nominal (a head with one)");
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
  }

  void process(imagenets::Context& ctx) override {
    const RobotModel& model = robotModel(ctx.property<std::string>("description"));
    const auto& d = model.description();
    const auto arm = ctx.input<sensor_msgs::JointState>("arm_joints");
    const auto head = ctx.input<sensor_msgs::JointState>("head_joints");
    const auto arm_q = imagenets::blocks::jointPositions(*arm, d.arm.names(), "arm_joints");
    const auto head_q = imagenets::blocks::jointPositions(*head, d.head.names(), "head_joints");
    const Eigen::Isometry3d marker = model.marker(arm_q);
    auto pose = [&](const Eigen::Isometry3d& camera, const std::string& frame) {
      auto msg = boost::make_shared<geometry_msgs::PoseStamped>();
      msg->header.stamp = head->header.stamp;
      msg->header.frame_id = frame;
      msg->pose = imagenets::frames::toPose(camera.inverse() * marker);
      return msg;
    };
    ctx.output("left", pose(model.leftCamera(head_q), d.left_camera.frame));
    ctx.output("right", pose(model.rightCamera(head_q), d.right_camera_frame));
    if (!d.mono_camera.frame.empty()) ctx.output("mono", pose(model.monoCamera(head_q), d.mono_camera.frame));
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::PredictMarkerPose, "imagenets/PredictMarkerPose", "calibration",
                         "Gripper marker in the head cameras' frames (left, right, mono) from the nominal model");
