// Kinematics read from a URDF with KDL: FRIEND's URDF generated from its DH file, read back, gives
// the DH description's forward kinematics; a URDF with tilted axes, offset joint origins and a
// prismatic joint gives KDL's own; what does not fit is named.
#include "robot_description/urdf_kinematics.h"

#include <cstdlib>
#include <fstream>
#include <random>

#include <boost/filesystem.hpp>
#include <unistd.h>

#include <gtest/gtest.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include "robot_description/urdf_generator.h"

using namespace robot_description;

namespace {

void expectSame(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double tolerance, const std::string& what) {
  EXPECT_LT((a.translation() - b.translation()).norm(), tolerance) << what;
  EXPECT_LT(Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle(), tolerance) << what;
}

std::vector<double> randomPose(const KinematicChain& c, std::mt19937& rng) {
  std::vector<double> q;
  for (const auto& j : c.joints) q.push_back(std::uniform_real_distribution<double>(j.min, j.max)(rng));
  return q;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

// KDL's own forward kinematics of a chain at q.
Eigen::Isometry3d kdlEnd(const KDL::Chain& chain, const std::vector<double>& q) {
  KDL::ChainFkSolverPos_recursive solver(chain);
  KDL::JntArray kq(q.size());
  for (size_t i = 0; i < q.size(); ++i) kq(i) = q[i];
  KDL::Frame f;
  if (solver.JntToCart(kq, f) < 0) throw std::runtime_error("KDL's solver failed");
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    t.translation()[r] = f.p(r);
    for (int c = 0; c < 3; ++c) t.linear()(r, c) = f.M(r, c);
  }
  return t;
}

void checkRoundTrip(const RobotDescription& dh) {
  const UrdfKinematics urdf(generateUrdf(dh), "generated URDF");
  const RobotDescription read = withUrdfKinematics(dh, urdf, generatedUrdfLinks(dh));
  const RobotModel a(dh), b(read);
  // The fixed point: base -> head_link_0, the parent link of the pan joint.
  expectSame(read.head.mount, dh.head.mount, 1e-12, "head mount");
  ASSERT_EQ(read.arm.names(), dh.arm.names());
  ASSERT_EQ(read.head.names(), dh.head.names());
  for (size_t i = 0; i < dh.arm.joints.size(); ++i) {
    EXPECT_NEAR(read.arm.joints[i].min, dh.arm.joints[i].min, 1e-12) << dh.arm.joints[i].name;
    EXPECT_NEAR(read.arm.joints[i].max, dh.arm.joints[i].max, 1e-12) << dh.arm.joints[i].name;
    EXPECT_NEAR(read.arm.joints[i].max_velocity, dh.arm.joints[i].max_velocity, 1e-12) << dh.arm.joints[i].name;
  }
  EXPECT_NEAR(read.stereo_baseline, dh.stereo_baseline, 1e-12);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 100; ++trial) {
    const auto arm = randomPose(dh.arm, rng), head = randomPose(dh.head, rng);
    const std::string at = " (trial " + std::to_string(trial) + ")";
    const auto arm_a = dh.arm.linkFrames(arm), arm_b = read.arm.linkFrames(arm);
    for (size_t i = 0; i < arm_a.size(); ++i) expectSame(arm_b[i], arm_a[i], 1e-9, "arm link " + std::to_string(i) + at);
    const auto head_a = dh.head.linkFrames(head), head_b = read.head.linkFrames(head);
    for (size_t i = 0; i < head_a.size(); ++i) expectSame(head_b[i], head_a[i], 1e-9, "head link " + std::to_string(i) + at);
    expectSame(b.tcp(arm), a.tcp(arm), 1e-9, "tcp" + at);
    expectSame(b.marker(arm), a.marker(arm), 1e-9, "marker" + at);
    expectSame(b.handCamera(arm), a.handCamera(arm), 1e-9, "hand camera" + at);
    expectSame(b.ftSensor(arm), a.ftSensor(arm), 1e-9, "force-torque sensor" + at);
    expectSame(b.leftCamera(head), a.leftCamera(head), 1e-9, "left camera" + at);
    expectSame(b.rightCamera(head), a.rightCamera(head), 1e-9, "right camera" + at);
  }
}

}  // namespace

TEST(UrdfKinematics, FriendsUrdfFromItsDhFileGivesTheDhKinematics) {
  checkRoundTrip(loadRobotDescription("config/example/robot.yaml"));
}

TEST(UrdfKinematics, ZeroOffsetsAndAnotherMountSurviveTheRoundTrip) {
  // As a calibrated or a simulated true robot has them: offsets on every joint, the head moved.
  RobotDescription d = loadRobotDescription("config/example/robot.yaml");
  for (size_t i = 0; i < d.arm.joints.size(); ++i) d.arm.joints[i].offset += 0.01 * (i + 1) - 0.03;
  for (auto& j : d.head.joints) j.offset -= 0.02;
  d.head.mount = fromXyzRpy({-0.04, 0.015, 1.36}, {0.02, -0.03, 0.05});
  checkRoundTrip(d);
}

TEST(UrdfKinematics, AGeneralUrdfGivesKdlsOwnForwardKinematics) {
  // Tilted axes, joint origins with translation and rotation, a prismatic joint, fixed links in
  // between: the chain read from it must move as KDL's own solver computes.
  const std::string xml = R"(<?xml version="1.0"?>
<robot name="general">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/><link name="tip"/>
  <joint name="mast" type="fixed"><parent link="base"/><child link="a"/><origin xyz="0.1 -0.2 0.5" rpy="0.1 0.2 0.3"/></joint>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.2" rpy="0 0.4 0"/>
    <axis xyz="0 1 1"/><limit lower="-2" upper="2" effort="1" velocity="1.5"/></joint>
  <joint name="slide" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.3 0 0" rpy="0 0 0.5"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.4" effort="1" velocity="0.2"/></joint>
  <joint name="bracket" type="fixed"><parent link="c"/><child link="d"/><origin xyz="0 0.05 0" rpy="-0.3 0 0"/></joint>
  <joint name="j3" type="continuous"><parent link="d"/><child link="e"/><origin xyz="0.1 0.1 0.1" rpy="1 0 0"/>
    <axis xyz="-1 0.5 0.2"/></joint>
  <joint name="flange" type="fixed"><parent link="e"/><child link="tip"/><origin xyz="0 0 0.08" rpy="0 0 1"/></joint>
</robot>)";
  const UrdfKinematics urdf(xml, "general.urdf");
  const KinematicChain chain = urdf.chain("base", "tip");
  ASSERT_EQ(chain.names(), (std::vector<std::string>{"j1", "slide", "j3"}));
  EXPECT_TRUE(chain.joints[1].prismatic);
  EXPECT_NEAR(chain.joints[0].max_velocity, 1.5, 1e-12);
  EXPECT_NEAR(chain.joints[1].max, 0.4, 1e-12);
  EXPECT_TRUE(std::isinf(chain.joints[2].max));  // continuous
  expectSame(chain.mount, fromXyzRpy({0.1, -0.2, 0.5}, {0.1, 0.2, 0.3}), 1e-12, "mount = the fixed joints before j1");

  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromString(xml, tree));
  KDL::Chain kdl_chain;
  ASSERT_TRUE(tree.getChain("base", "tip", kdl_chain));
  std::mt19937 rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> v;
    for (int i = 0; i < 3; ++i) v.push_back(std::uniform_real_distribution<double>(-2, 2)(rng));
    expectSame(chain.end(v), kdlEnd(kdl_chain, v), 1e-9, "trial " + std::to_string(trial));
  }
  expectSame(urdf.fixedTransform("c", "d"), fromXyzRpy({0, 0.05, 0}, {-0.3, 0, 0}), 1e-12, "bracket");
}

TEST(UrdfKinematics, ARobotThatExistsOnlyAsAUrdfLoadsThroughItsDescription) {
  // config/six_axis: robot.yaml names the links of robot.urdf; its chains are KDL's.
  const RobotDescription d = loadRobotDescription("config/six_axis/robot.yaml");
  ASSERT_EQ(d.arm.names(), (std::vector<std::string>{"shoulder_pan", "shoulder_lift", "elbow", "forearm_roll",
                                                     "wrist_pitch", "flange_roll"}));
  ASSERT_EQ(d.head.names(), (std::vector<std::string>{"pan", "tilt"}));
  // The fixed point: base_link -> head_mount, the parent link of the pan joint.
  expectSame(d.head.mount, fromXyzRpy({-0.08, 0.04, 1.28}, {0, 0, 0}), 1e-12, "head mount");
  EXPECT_NEAR(d.stereo_baseline, 0.12, 1e-12);
  EXPECT_EQ(d.marker.frame, "gripper_marker");
  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromFile("config/six_axis/robot.urdf", tree));
  KDL::Chain to_marker;
  ASSERT_TRUE(tree.getChain("base_link", "gripper_marker", to_marker));
  const RobotModel model(d);
  std::mt19937 rng(9);
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = randomPose(d.arm, rng);
    expectSame(model.marker(q), kdlEnd(to_marker, q), 1e-9, "marker, trial " + std::to_string(trial));
  }
  // The URDF generated from it (the simulator's robot_state_publisher) gives the same kinematics.
  checkRoundTrip(d);
}

TEST(UrdfKinematics, AMonoCameraOnTheHeadIsReadBesideTheStereoPair) {
  // config/mobile_manipulator: its RGB camera between the stereo cameras, 0.03 m above them.
  const RobotModel m(loadRobotDescription("config/mobile_manipulator/robot.yaml"));
  const auto& d = m.description();
  EXPECT_EQ(d.arm.joints.size(), 7u);
  EXPECT_EQ(d.mono_camera.frame, "head_camera_rgb_optical_frame");
  EXPECT_NE(d.mono_camera_info.find("mobile_manipulator/head_camera_rgb.yaml"), std::string::npos);
  const std::vector<double> head{0.3, -0.2};
  const Eigen::Isometry3d in_left = m.leftCamera(head).inverse() * m.monoCamera(head);
  EXPECT_LT((in_left.translation() - Eigen::Vector3d(0.06, -0.03, 0)).norm(), 1e-12);
  EXPECT_LT(Eigen::AngleAxisd(in_left.linear()).angle(), 1e-12);
  // A description without one has none.
  EXPECT_TRUE(loadRobotDescription("config/six_axis/robot.yaml").mono_camera.frame.empty());
}

TEST(UrdfKinematics, TheCalibrationCameraIsTheStereoPairUnlessTheMonoOneIsChosen) {
  const RobotDescription d = loadRobotDescription("config/mobile_manipulator/robot.yaml");
  EXPECT_EQ(d.calibration_camera, "stereo");
  const std::vector<double> head{0.3, -0.2};
  EXPECT_TRUE(RobotModel(d).calibrationCamera(head).isApprox(RobotModel(d).leftCamera(head), 1e-12));
  const RobotModel mono(withCalibrationCamera(d, "mono", "~calibration_camera"));
  EXPECT_EQ(mono.description().calibration_camera, "mono");
  EXPECT_TRUE(mono.calibrationCamera(head).isApprox(mono.monoCamera(head), 1e-12));
  EXPECT_NE(messageOf([&] { withCalibrationCamera(d, "left", "~calibration_camera"); })
                .find("~calibration_camera: 'left' is no calibration camera (expected 'stereo' or 'mono')"),
            std::string::npos);
  const RobotDescription six = loadRobotDescription("config/six_axis/robot.yaml");
  EXPECT_NE(messageOf([&] { withCalibrationCamera(six, "mono", "x.yaml: head.calibration_camera"); })
                .find("x.yaml: head.calibration_camera: 'mono', but " + six.source + " gives the head no mono camera"),
            std::string::npos);
  // The key in a description file.
  const std::string path = "/tmp/urdf_kinematics_test_mono_" + std::to_string(::getpid()) + ".yaml";
  {
    std::ifstream in("config/mobile_manipulator/robot.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string key = "  calibration_pose_deg: [10.2, 25.4]";
    ASSERT_NE(text.find(key), std::string::npos);
    text.replace(text.find(key), 0, "  calibration_camera: mono\n");
    // (The URDF is read; the camera_info files only named.)
    // (The description's paths are relative to its folder.)
    text.replace(text.find("urdf: robot.urdf"), 16,
                 "urdf: " + boost::filesystem::relative(boost::filesystem::absolute("config/mobile_manipulator/robot.urdf"),
                                                        boost::filesystem::path(path).parent_path())
                                .string());
    std::ofstream(path) << text;
  }
  EXPECT_EQ(loadRobotDescription(path).calibration_camera, "mono");
  std::remove(path.c_str());
}

TEST(UrdfKinematics, WhatDoesNotFitIsNamed) {
  EXPECT_NE(messageOf([] { UrdfKinematics("<robot name='x'><link name='a'/>", "broken.urdf"); }).find("broken.urdf: not a valid URDF"),
            std::string::npos);
  EXPECT_NE(messageOf([] { UrdfKinematics::fromFile("/nonexistent/robot.urdf"); }).find("'/nonexistent/robot.urdf': cannot read"),
            std::string::npos);
  const RobotDescription d = loadRobotDescription("config/example/robot.yaml");
  const UrdfKinematics urdf(generateUrdf(d), "friend.urdf");
  EXPECT_EQ(urdf.rootLink(), "base_link");
  EXPECT_NE(messageOf([&] { urdf.chain("base_link", "no_such_link"); }).find("friend.urdf: the URDF has no link 'no_such_link'"),
            std::string::npos);
  // Fixed joints only: a chain without joints whose mount is the whole way (a camera on a stand).
  const KinematicChain fixed_only = urdf.chain("arm_link_7", "tcp");
  EXPECT_TRUE(fixed_only.joints.empty());
  EXPECT_EQ(fixed_only.tip_link, "tcp");
  EXPECT_TRUE(fixed_only.mount.isApprox(urdf.fixedTransform("arm_link_7", "tcp"), 1e-12));
  UrdfLinks no_arm = generatedUrdfLinks(d);
  no_arm.arm_tip = no_arm.base;  // an arm must move
  EXPECT_NE(messageOf([&] { withUrdfKinematics(d, urdf, no_arm); })
                .find("friend.urdf: the arm chain from link 'base_link' to link 'base_link' has no moving joint"),
            std::string::npos);
  EXPECT_NE(messageOf([&] { urdf.fixedTransform("arm_link_6", "tcp"); }).find("joint 'arm_joint_7' moves between them"),
            std::string::npos);
  UrdfLinks links = generatedUrdfLinks(d);
  links.left_camera = links.head_tip;  // the right optical frame is then turned against it
  EXPECT_NE(messageOf([&] { withUrdfKinematics(d, urdf, links); })
                .find("link 'stereo_right_optical_frame' must be link 'head_link_2' moved along its x axis"),
            std::string::npos);
}

TEST(UrdfKinematics, ACameraOnAStandIsAHeadWithoutJoints) {
  // config/ur_stand: a UR5-like arm and a stereo camera on a stand; the head chain base_link ->
  // camera_mount_link has fixed joints only, so its mount (the fixed point) is the whole way.
  const RobotDescription d = loadRobotDescription("config/ur_stand/robot.yaml");
  ASSERT_EQ(d.arm.names(), (std::vector<std::string>{"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                                     "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"}));
  EXPECT_TRUE(d.head.joints.empty());
  EXPECT_EQ(d.head.tip_link, "camera_mount_link");
  EXPECT_TRUE(d.head_calibration_pose.empty());
  EXPECT_TRUE(d.head_home.empty());
  EXPECT_NEAR(d.stereo_baseline, 0.12, 1e-12);
  const UrdfKinematics urdf = UrdfKinematics::fromFile("config/ur_stand/robot.urdf");
  expectSame(d.head.mount, urdf.fixedTransform("base_link", "camera_mount_link"), 1e-12, "camera mount");
  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromFile("config/ur_stand/robot.urdf", tree));
  KDL::Chain to_target, to_left;
  ASSERT_TRUE(tree.getChain("base_link", "target_mount_link", to_target));
  ASSERT_TRUE(tree.getChain("base_link", "stereo_left_optical_frame", to_left));
  const RobotModel model(d);
  expectSame(model.leftCamera({}), kdlEnd(to_left, {}), 1e-9, "left camera");
  std::mt19937 rng(4);
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = randomPose(d.arm, rng);
    expectSame(model.marker(q), kdlEnd(to_target, q), 1e-9, "target, trial " + std::to_string(trial));
  }
  // What a calibration estimates: the camera mount, the target offset, arm joints 2..5 (the
  // first turns like the mount, the last like the target); no head joint.
  const FreeParams f = freeParams(d);
  EXPECT_TRUE(f.fixed_point && f.target_offset);
  EXPECT_EQ(f.arm, (std::vector<size_t>{1, 2, 3, 4}));
  EXPECT_TRUE(f.head.empty());
  // A camera that cannot turn cannot look at a point.
  EXPECT_NE(messageOf([&] { model.lookAt(Eigen::Vector3d(0.5, 0, 0.3)); }).find("only a pan-tilt head can look at a point"),
            std::string::npos);
  // Its calibration pose shows the target's face to both cameras about 1 m away, in the image.
  const Eigen::Isometry3d target = model.marker(d.arm_calibration_pose);
  for (const Eigen::Isometry3d& cam : {model.leftCamera({}), model.rightCamera({})}) {
    const Eigen::Isometry3d in_cam = cam.inverse() * target;
    const Eigen::Vector3d c = in_cam.translation();
    EXPECT_GT(c.z(), 0.9);
    EXPECT_LT(c.z(), 1.1);
    EXPECT_LT(std::abs(1400 * c.x() / c.z()), 200) << c.transpose();
    EXPECT_LT(std::abs(1400 * c.y() / c.z()), 150) << c.transpose();
    EXPECT_GT(in_cam.linear().col(2).dot(-c.normalized()), std::cos(20 * M_PI / 180));
  }
}

TEST(UrdfKinematics, AHeadOfOneJointIsRefused) {
  // The UR arm's URDF with the head ending one joint after the base: neither pan-tilt nor a stand.
  std::ifstream in("config/ur_stand/robot.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string stand = "<parent link=\"base_link\"/><child link=\"camera_stand_link\"/>";
  ASSERT_NE(urdf.find(stand), std::string::npos);
  urdf.replace(urdf.find(stand), stand.size(), "<parent link=\"shoulder_link\"/><child link=\"camera_stand_link\"/>");
  const std::string dir = "/tmp/ur_stand_one_joint_" + std::to_string(::getpid());
  ASSERT_EQ(system(("mkdir -p " + dir).c_str()), 0);
  std::ofstream(dir + "/robot.urdf") << urdf;
  std::ifstream yaml_in("config/ur_stand/robot.yaml");
  std::string yaml((std::istreambuf_iterator<char>(yaml_in)), std::istreambuf_iterator<char>());
  for (const std::string info : {"../example/stereo_left.yaml", "../example/stereo_right.yaml"}) {
    yaml.replace(yaml.find(info), info.size(), "stereo.yaml");  // not read by the loader
  }
  std::ofstream(dir + "/robot.yaml") << yaml;
  EXPECT_NE(messageOf([&] { loadRobotDescription(dir + "/robot.yaml"); })
                .find("robot.yaml: head.tip_link: a head has 2 joints (pan, tilt) or none (a camera on a stand), not 1"),
            std::string::npos)
      << messageOf([&] { loadRobotDescription(dir + "/robot.yaml"); });
}
