#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <ros/package.h>

#include "robot_description/robot_model.h"
#include "robot_description/urdf_kinematics.h"

using namespace robot_description;

namespace {
constexpr double kDeg = M_PI / 180.0;

double angleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

std::string writeTemp(const std::string& text) {
  char name[] = "/tmp/friend_desc_XXXXXX";
  const int fd = mkstemp(name);
  close(fd);
  std::ofstream(name) << text;
  return name;
}

// The config `text` loaded from a temporary file: that file's path and the error ("no error").
std::pair<std::string, std::string> errorOf(const std::string& text) {
  const std::string path = writeTemp(text);
  std::string what = "no error";
  try {
    loadRobotDescription(path);
  } catch (const std::runtime_error& e) {
    what = e.what();
  }
  std::remove(path.c_str());
  return std::make_pair(path, what);
}

// `text` with the first `from` replaced by `to` (a test failure when it has no `from`).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// The file's text (this package does not depend on imagenets, whose tests share a readFile).
std::string fileText(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
}  // namespace

TEST(RobotModel, LoadsTheShippedDescription) {
  const auto d = loadRobotDescription("config/example/robot.yaml");
  EXPECT_EQ(d.arm.joints.size(), 7u);
  EXPECT_EQ(d.head.joints.size(), 2u);
  EXPECT_DOUBLE_EQ(d.marker_size, 0.06);
  EXPECT_NEAR(d.stereo_baseline, 0.12, 1e-12);
  EXPECT_EQ(d.arm.joints[0].name, "arm_joint_1");
  // Its DH row as a chain joint: axis z, tip Tz(d) Rx(alpha).
  EXPECT_TRUE(d.arm.joints[0].axis.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(d.arm.joints[0].tip.isApprox(Eigen::Translation3d(0, 0, 0.3) * Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX())));
  EXPECT_NE(d.left_camera_info.find("config/example/stereo_left.yaml"), std::string::npos);
}

TEST(RobotModel, DhTransformFollowsTheClassicConvention) {
  DhJoint j;
  j.a = 0.2;
  j.d = 0.1;
  j.alpha = M_PI / 2;
  j.theta_offset = 0.1;
  const Eigen::Isometry3d t = dhTransform(j, 0.3);
  const double th = 0.4;
  Eigen::Matrix4d expected;
  expected << std::cos(th), -std::sin(th) * std::cos(j.alpha), std::sin(th) * std::sin(j.alpha), j.a * std::cos(th),
      std::sin(th), std::cos(th) * std::cos(j.alpha), -std::cos(th) * std::sin(j.alpha), j.a * std::sin(th), 0,
      std::sin(j.alpha), std::cos(j.alpha), j.d, 0, 0, 0, 1;
  EXPECT_TRUE(t.matrix().isApprox(expected, 1e-12)) << t.matrix() << "\n" << expected;
}

TEST(RobotModel, RpyRoundTripIncludingGimbalLock) {
  for (const Eigen::Vector3d rpy : {Eigen::Vector3d(0.1, -0.4, 2.0), Eigen::Vector3d(0, M_PI / 2, 0),
                                    Eigen::Vector3d(0.3, -M_PI / 2, 0.2), Eigen::Vector3d(-3.0, 0.01, -1.0)}) {
    const Eigen::Matrix3d r = fromXyzRpy(Eigen::Vector3d::Zero(), rpy).linear();
    const Eigen::Matrix3d back = fromXyzRpy(Eigen::Vector3d::Zero(), rpyOf(r)).linear();
    EXPECT_LT(angleBetween(r, back), 1e-9) << rpy.transpose();
  }
}

TEST(RobotModel, LimitViolationNamesTheJoint) {
  const auto d = loadRobotDescription("config/example/robot.yaml");
  std::vector<double> q(7, 0.0);
  EXPECT_EQ(d.arm.limitViolation(q), "");
  q[3] = 2.5;  // joint 4 is limited to +-115 deg
  const std::string why = d.arm.limitViolation(q);
  EXPECT_NE(why.find("arm_joint_4"), std::string::npos) << why;
  EXPECT_NE(why.find("115"), std::string::npos) << why;
  EXPECT_NE(d.arm.limitViolation({0, 0}).find("expected 7"), std::string::npos);
}

TEST(RobotModel, BadDescriptionsAreReportedWithFileAndKey) {
  EXPECT_THROW(loadRobotDescription("/nonexistent/robot.yaml"), std::runtime_error);
  const std::string path = writeTemp("arm:\n  mount: {xyz: [0, 0, 0]}\n  joints:\n    - {name: j1, a: 0, d: 1}\n");
  try {
    loadRobotDescription(path);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("alpha_deg"), std::string::npos) << what;
  }
  std::remove(path.c_str());
}

TEST(RobotModel, LookAtCentresTheTargetBetweenTheStereoCameras) {
  const RobotModel m(loadRobotDescription("config/example/robot.yaml"));
  const Eigen::Vector3d target = m.tcp(m.description().arm_calibration_pose).translation();
  const auto pt = m.lookAt(target);
  Eigen::Isometry3d centre = m.leftCamera({pt[0], pt[1]});
  centre.translate(Eigen::Vector3d(m.description().stereo_baseline / 2, 0, 0));
  const Eigen::Vector3d p = centre.inverse() * target;
  EXPECT_GT(p.z(), 0.3);
  EXPECT_LT(std::hypot(p.x(), p.y()) / p.z(), 1e-6) << p.transpose();
}

TEST(RobotModel, CalibrationPoseShowsTheMarkerToBothCameras) {
  const RobotModel m(loadRobotDescription("config/example/robot.yaml"));
  const auto& d = m.description();
  const Eigen::Isometry3d marker = m.marker(d.arm_calibration_pose);
  for (const Eigen::Isometry3d& cam : {m.leftCamera(d.head_calibration_pose), m.rightCamera(d.head_calibration_pose)}) {
    const Eigen::Isometry3d in_cam = cam.inverse() * marker;
    const Eigen::Vector3d c = in_cam.translation();
    ASSERT_GT(c.z(), 0.3);
    EXPECT_LT(c.z(), 1.2);
    // Roughly inside a 1400 px focal length image of 1024 x 768 (with margin).
    EXPECT_LT(std::abs(1400 * c.x() / c.z()), 400) << c.transpose();
    EXPECT_LT(std::abs(1400 * c.y() / c.z()), 300) << c.transpose();
    // The printed face points towards the camera, not more than 50 degrees off.
    const Eigen::Vector3d normal = in_cam.linear().col(2);
    const double cosang = normal.dot(-c.normalized());
    EXPECT_GT(cosang, std::cos(50 * kDeg)) << "marker normal " << normal.transpose();
  }
}

TEST(RobotModel, FreeParamsNameWhatACalibrationEstimatesAndRefuseUnknownNames) {
  const std::string text = fileText(exampleRobotDescriptionPath());
  // Absent: everything that can be estimated (arm joints 2..n-1, the head joints after the pan).
  const RobotDescription all = loadRobotDescription(exampleRobotDescriptionPath());
  const FreeParams every = freeParams(all);
  EXPECT_TRUE(every.fixed_point && every.target_offset);
  EXPECT_EQ(every.arm, (std::vector<size_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(every.head, (std::vector<size_t>{1}));
  // Named: only those.
  const std::string two = writeTemp(text + "\nfree_params: [fixed_point, " + all.arm.joints[2].name + "]\n");
  const FreeParams some = freeParams(loadRobotDescription(two));
  EXPECT_TRUE(some.fixed_point);
  EXPECT_FALSE(some.target_offset);
  EXPECT_EQ(some.arm, (std::vector<size_t>{2}));
  EXPECT_TRUE(some.head.empty());
  std::remove(two.c_str());
  // An unknown name, and the first arm joint (whose offset no such calibration can tell from a
  // turn of the head mount): errors naming the file, the key and the name.
  for (const std::string& bad : {std::string("elbow"), all.arm.joints[0].name}) {
    const std::string path = writeTemp(text + "\nfree_params: [fixed_point, " + bad + "]\n");
    try {
      loadRobotDescription(path);
      ADD_FAILURE() << "expected an error for " << bad;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path + ": free_params"), std::string::npos) << what;
      EXPECT_NE(what.find("unknown parameter '" + bad + "'"), std::string::npos) << what;
      EXPECT_NE(what.find("known: fixed_point, target_offset, joint_offsets, " + all.arm.joints[1].name), std::string::npos)
          << what;
    }
    std::remove(path.c_str());
  }
}

// The calibration config names no URDF: the file given instead (the offline calibration's --urdf)
// gives the same robot as the robot.yaml that names it; without one, and outside a ROS node (no
// parameter server to read robot_description from), the error says what to give.
TEST(RobotModel, ACalibrationConfigWithoutAUrdfFileTakesTheOneGivenOrSaysWhatIsMissing) {
  const std::string dir = ros::package::getPath("robot_description") + "/config/six_axis/";
  try {
    loadRobotDescription(dir + "calibration.yaml");
    ADD_FAILURE() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dir + "calibration.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("names no URDF file"), std::string::npos) << what;
    EXPECT_NE(what.find("--urdf FILE"), std::string::npos) << what;
  }
  useUrdfFile(dir + "robot.urdf");
  const RobotDescription config = loadRobotDescription(dir + "calibration.yaml");
  useUrdfFile("");
  const RobotDescription robot = loadRobotDescription(dir + "robot.yaml");
  ASSERT_EQ(config.arm.joints.size(), 6u);
  ASSERT_EQ(config.arm.joints.size(), robot.arm.joints.size());
  for (size_t j = 0; j < robot.arm.joints.size(); ++j) {
    EXPECT_EQ(config.arm.joints[j].name, robot.arm.joints[j].name);
    EXPECT_EQ(config.arm.joints[j].origin.matrix(), robot.arm.joints[j].origin.matrix());
  }
  EXPECT_EQ(config.head.mount.matrix(), robot.head.mount.matrix());
  EXPECT_EQ(config.marker.pose.matrix(), robot.marker.pose.matrix());
  EXPECT_EQ(config.left_camera_info, robot.left_camera_info);
  EXPECT_EQ(config.free_params, (std::vector<std::string>{"fixed_point", "target_offset", "joint_offsets"}));
}

// Bad calibration configs: each error names the file, the key or link, and what is wrong.
TEST(RobotModel, BadCalibrationConfigsAreClearErrors) {
  const std::string dir = ros::package::getPath("robot_description") + "/config/six_axis/";
  const std::string config = fileText(dir + "calibration.yaml");
  useUrdfFile(dir + "robot.urdf");
  // An unknown key, at the top and inside a group.
  auto [path, what] = errorOf(config + "\nfree_parms: [fixed_point]\n");
  EXPECT_NE(what.find(path + ": unknown key 'free_parms' (known: urdf, name, base_frame, free_params, arm, head)"),
            std::string::npos)
      << what;
  std::tie(path, what) = errorOf(replaced(config, "  tip_link: flange", "  tip_lnk: flange"));
  EXPECT_NE(what.find(path + ": arm: unknown key 'tip_lnk'"), std::string::npos) << what;
  // A link the URDF lacks.
  std::tie(path, what) = errorOf(replaced(config, "tip_link: flange", "tip_link: no_such_flange"));
  EXPECT_NE(what.find("no_such_flange"), std::string::npos) << what;
  EXPECT_NE(what.find(dir + "robot.urdf"), std::string::npos) << what;
  // An interface's name that is no string, or no valid ROS name.
  std::tie(path, what) = errorOf(replaced(config, "  tip_link: flange", "  tip_link: flange\n  controller: [a, b]"));
  EXPECT_NE(what.find(path + ": arm.controller: expected a ROS name"), std::string::npos) << what;
  std::tie(path, what) = errorOf(replaced(config, "    left_link:", "    namespace: 'stereo pair'\n    left_link:"));
  EXPECT_NE(what.find(path + ": head.stereo_camera.namespace: 'stereo pair' is no valid ROS name"), std::string::npos)
      << what;
  std::tie(path, what) =
      errorOf(replaced(config, "  tip_link: head_tilt_link", "  tip_link: head_tilt_link\n  controler: x"));
  EXPECT_NE(what.find(path + ": head: unknown key 'controler' (known: "), std::string::npos) << what;
  // A URDF that does not parse: the file and the parser's own reason.
  const std::string broken = writeTemp("<robot name='cut short'><link name='base_link'/><joint");
  useUrdfFile(broken);
  std::tie(path, what) = errorOf(config);
  EXPECT_NE(what.find(broken), std::string::npos) << what;
  EXPECT_NE(what.find(": not a valid URDF: Failed to read Element name"), std::string::npos) << what;  // tinyxml2's
  std::remove(broken.c_str());
  useUrdfFile("");
}

// head.mono_camera.namespace is checked as head.stereo_camera.namespace is: a value that is no valid
// ROS name is refused, naming the file, the key and the value.
TEST(RobotModel, AMonoCameraNamespaceThatIsNoRosNameIsAClearError) {
  const std::string dir = ros::package::getPath("robot_description") + "/config/mobile_manipulator/";
  const std::string config = fileText(dir + "calibration.yaml");
  useUrdfFile(dir + "robot.urdf");
  auto [path, what] = errorOf(config);
  EXPECT_EQ(what, "no error");  // the shipped config loads from the temporary file's folder too
  std::tie(path, what) = errorOf(replaced(config, "    namespace: head_camera", "    namespace: 'head camera'"));
  EXPECT_NE(what.find(path + ": head.mono_camera.namespace: 'head camera' is no valid ROS name"), std::string::npos)
      << what;
  std::tie(path, what) = errorOf(replaced(config, "    namespace: head_camera", "    namespace: [head_camera]"));
  EXPECT_NE(what.find(path + ": head.mono_camera.namespace: expected a ROS name"), std::string::npos) << what;
  useUrdfFile("");
}

// The robot's interfaces in its calibration config: read when named, empty (the nets' own) when not.
TEST(RobotModel, ACalibrationConfigNamesTheRobotsControllersAndCameraTopics) {
  const std::string dir = ros::package::getPath("robot_description") + "/config/";
  useUrdfFile(dir + "mobile_manipulator/robot.urdf");
  const RobotDescription d = loadRobotDescription(dir + "mobile_manipulator/calibration.yaml");
  useUrdfFile("");
  EXPECT_EQ(d.arm_controller, "arm_controller/follow_joint_trajectory");
  EXPECT_EQ(d.head_controller, "head_controller/follow_joint_trajectory");
  EXPECT_EQ(d.stereo_namespace, "stereo");
  EXPECT_EQ(d.mono_namespace, "head_camera");
  EXPECT_EQ(d.arm.joints.size(), 7u);
  EXPECT_EQ(d.mono_camera.frame, "head_camera_rgb_optical_frame");
  // The same robot with its URDF named (robot.yaml) and FRIEND's DH form name none.
  for (const std::string& file : {dir + "mobile_manipulator/robot.yaml", dir + "example/robot.yaml"}) {
    const RobotDescription other = loadRobotDescription(file);
    EXPECT_EQ(other.arm_controller + other.head_controller + other.stereo_namespace + other.mono_namespace, "") << file;
  }
}

