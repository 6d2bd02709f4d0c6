// A robot's own URDF with changed kinematics (a calibration, the simulator's true robot) written
// into it: the links and joints keep their names, the URDF read back gives the changed
// kinematics; a description of DH tables gets the generated URDF.
#include "robot_description/urdf_writer.h"

#include <gtest/gtest.h>

#include "robot_description/urdf_generator.h"
#include "robot_description/urdf_kinematics.h"

using namespace robot_description;

namespace {

void expectSame(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const std::string& what) {
  EXPECT_LT((a.translation() - b.translation()).norm(), 1e-9) << what;
  EXPECT_LT(Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle(), 1e-9) << what;
}

// A calibration's kind of change: head mount, marker, joint zero offsets.
RobotDescription changedFrom(const RobotDescription& nominal) {
  RobotDescription c = nominal;
  c.head.mount = fromXyzRpy({0.011, -0.007, 0.009}, {0.02, -0.015, 0.03}) * nominal.head.mount;
  c.marker.pose = nominal.marker.pose * fromXyzRpy({0.0008, -0.0005, 0.0002}, {0.004, -0.003, 0.002});
  for (size_t i = 0; i < c.arm.joints.size(); ++i) c.arm.joints[i].offset += 0.001 * (i + 1);
  c.head.joints[1].offset += -0.0015;
  return c;
}

}  // namespace

TEST(UrdfWriter, ARobotsOwnUrdfKeepsItsNamesAndTakesTheChangedKinematics) {
  const auto nominal = loadRobotDescription("config/six_axis/robot.yaml");
  ASSERT_EQ(urdfFileOf(nominal), "config/six_axis/robot.urdf");
  const RobotDescription changed = changedFrom(nominal);
  const std::string text = writeUrdf(nominal, changed, "ignored", "calibrated -- by a test");
  // Its own names: the robot, the head's mount joint, every chain joint; no generated link.
  EXPECT_NE(text.find("<robot name=\"six_axis\">"), std::string::npos);
  EXPECT_NE(text.find("<joint name=\"head_mast\" type=\"fixed\">"), std::string::npos);
  EXPECT_NE(text.find("<joint name=\"shoulder_lift\" type=\"revolute\">"), std::string::npos);
  EXPECT_EQ(text.find("head_link_0"), std::string::npos);
  EXPECT_EQ(text.find("_rotor"), std::string::npos);
  EXPECT_NE(text.find("calibrated - - by a test"), std::string::npos) << "the note, legal in an XML comment";
  // Read back with KDL over the same links, it is the changed robot.
  UrdfLinks links;
  links.base = "base_link";
  links.arm_tip = "flange";
  links.tool = "tcp";
  links.marker = "gripper_marker";
  links.hand_camera = "hand_camera_optical_frame";
  links.ft_sensor = "ft_sensor";
  links.head_tip = "head_tilt_link";
  links.left_camera = "stereo_left_optical_frame";
  links.right_camera = "stereo_right_optical_frame";
  const RobotModel back(withUrdfKinematics(nominal, UrdfKinematics(text, "written URDF"), links)), want(changed);
  expectSame(back.headBase(), want.headBase(), "head mount");
  const std::vector<double> arm{0.3, -0.4, 0.9, 0.2, -0.6, 1.1}, head{0.25, 0.35};
  expectSame(back.marker(arm), want.marker(arm), "marker");
  expectSame(back.tcp(arm), want.tcp(arm), "tcp");
  expectSame(back.handCamera(arm), want.handCamera(arm), "hand camera");
  expectSame(back.leftCamera(head), want.leftCamera(head), "left camera");
  expectSame(back.rightCamera(head), want.rightCamera(head), "right camera");
  // The joints that hold the calibration, as the calibrated URDF's note names them.
  const UrdfJoint mount = urdfChainMountJoint(nominal, nominal.head);
  EXPECT_EQ(mount.name, "head_mast");
  EXPECT_EQ(mount.parent, "base_link");
  EXPECT_EQ(mount.child, "head_mount");
  EXPECT_EQ(urdfFixedJoint(nominal, nominal.marker.frame).name, "gripper_marker_joint");
}

TEST(UrdfWriter, UnchangedKinematicsLeaveEveryJointAsWritten) {
  const auto nominal = loadRobotDescription("config/six_axis/robot.yaml");
  const std::string text = writeUrdf(nominal, nominal, "six_axis");
  EXPECT_NE(text.find("<origin xyz=\"0 0.05 0\" rpy=\"0 0 0\"/>"), std::string::npos) << text;
  EXPECT_NE(text.find("<origin xyz=\"-0.08 0.04 1.28\" rpy=\"0 0 0\"/>"), std::string::npos) << text;
}

TEST(UrdfWriter, ADescriptionOfDhTablesGetsTheGeneratedUrdf) {
  const auto nominal = loadRobotDescription("config/example/robot.yaml");
  EXPECT_EQ(urdfFileOf(nominal), "");
  const RobotDescription changed = changedFrom(nominal);
  EXPECT_EQ(writeUrdf(nominal, changed, "friend", "note"), generateUrdf(changed, "friend", "note"));
  EXPECT_EQ(urdfChainMountJoint(nominal, nominal.head).name, "head_link_0_mount");
}

TEST(UrdfWriter, ALinkThatNoFixedJointPlacesIsNamed) {
  const auto nominal = loadRobotDescription("config/six_axis/robot.yaml");
  try {
    urdfFixedJoint(nominal, "shoulder");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("config/six_axis/robot.urdf': link 'shoulder' (a fixed frame) hangs from joint "
                                         "'shoulder_pan', which is not fixed"),
              std::string::npos)
        << e.what();
  }
}

TEST(UrdfWriter, ACameraOnAStandTakesItsMountIntoTheJointToTheCameraMount) {
  // A head without joints: its mount (the fixed point) goes into the fixed joint whose child is
  // the chain's tip link, the stand's camera mount.
  const auto nominal = loadRobotDescription("config/ur_stand/robot.yaml");
  const UrdfJoint mount = urdfChainMountJoint(nominal, nominal.head);
  EXPECT_EQ(mount.name, "camera_mount_joint");
  EXPECT_EQ(mount.parent, "camera_stand_link");
  EXPECT_EQ(mount.child, "camera_mount_link");
  RobotDescription changed = nominal;
  changed.head.mount = fromXyzRpy({0.004, -0.003, 0.003}, {0.005, -0.004, 0.005}) * nominal.head.mount;
  changed.arm.joints[2].offset += 0.001;
  const std::string text = writeUrdf(nominal, changed, "ignored");
  UrdfLinks links;
  links.base = "base_link";
  links.arm_tip = "wrist_3_link";
  links.tool = "tool0";
  links.marker = "target_mount_link";
  links.hand_camera = "wrist_camera_optical_frame";
  links.ft_sensor = "ft_frame";
  links.head_tip = "camera_mount_link";
  links.left_camera = "stereo_left_optical_frame";
  links.right_camera = "stereo_right_optical_frame";
  const RobotModel back(withUrdfKinematics(nominal, UrdfKinematics(text, "written URDF"), links)), want(changed);
  EXPECT_TRUE(back.description().head.joints.empty());
  expectSame(back.headBase(), want.headBase(), "camera mount");
  expectSame(back.leftCamera({}), want.leftCamera({}), "left camera");
  const std::vector<double> arm{0.1, -1.1, 1.9, 1.7, -0.9, -2.7};
  expectSame(back.marker(arm), want.marker(arm), "target");
}
