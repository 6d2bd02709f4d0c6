// rostest: the calibration node given bad input says what is wrong, naming it, and leaves the
// previous calibration file as it was (see calibration_bad_input.test). The test starts the node
// itself, once per case, and reads what it prints (a message on /rosout sent while the node starts
// could be lost before this test's connection is up).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/package_file.h"
#include "imagenets/testing/rostest_util.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "files_and_processes.h"

namespace {

namespace fs = std::filesystem;

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("calibration_bad_input_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    previous_ = readFile(fs::path(IMAGENETS_SOURCE_DIR) / "test/pth_fixed_point.yaml");
    ASSERT_FALSE(previous_.empty());
  }
  void TearDown() override {
    node_process_.stop();
    fs::remove_all(dir_);
  }

  // Starts the calibration node `name` with its calibration config `config` and the extra
  // arguments; a calibration file from before beside; its output goes to a log file.
  void startNode(const std::string& name, const std::string& config, std::vector<std::string> extra) {
    file_ = (dir_ / (name + ".yaml")).string();
    std::ofstream(file_, std::ios::binary) << previous_;
    log_ = (dir_ / (name + ".log")).string();
    node_ = "/" + name;
    std::vector<std::string> args{"stdbuf", "-oL", IMAGENETS_CALIBRATION_NODE, "__name:=" + name,
                                  "_calibration_file:=" + file_, "_server_timeout:=3.0", "_description:=" + config,
                                  "_marker:=" + imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"),
                                  "_net:=" + imagenets::packageFile("imagenets_calibration", "config/nets/calibration.yaml")};
    args.insert(args.end(), extra.begin(), extra.end());
    node_process_.start(args, log_);
    ASSERT_GT(node_process_.pid(), 0);
  }
  // Waits until the log holds `text`; the log.
  std::string logWith(const std::string& text, double seconds) {
    std::string log;
    waitFor(
        [&] {
          log = readFile(log_);
          return log.find(text) != std::string::npos;
        },
        seconds);
    return log;
  }

  fs::path dir_;
  std::string previous_, file_, log_, node_;
  ChildProcess node_process_;
};

// The mobile manipulator's calibration.yaml with `from` replaced by `to`, in the temporary folder
// (its camera files named by absolute paths).
std::string configWith(const std::string& from, const std::string& to, const std::string& name) {
  const fs::path original = imagenets::packageFile("robot_description", "config/mobile_manipulator/calibration.yaml");
  std::string text = readFile(original);
  auto replace = [&](const std::string& a, const std::string& b) {
    const size_t at = text.find(a);
    EXPECT_NE(at, std::string::npos) << a;
    if (at != std::string::npos) text.replace(at, a.size(), b);
  };
  replace(from, to);
  const std::string folder = original.parent_path().string() + "/";
  replace("left_camera_info: ", "left_camera_info: " + folder);
  replace("right_camera_info: ", "right_camera_info: " + folder);
  replace("camera_info: head_camera_rgb.yaml", "camera_info: " + folder + "head_camera_rgb.yaml");
  const fs::path out = fs::temp_directory_path() / name;
  std::ofstream(out) << text;
  return out.string();
}

TEST_F(BadInput, AControllerWithoutAnActionServerIsNamedAtStartUpAndByTheCalibration) {
  ASSERT_TRUE(ros::topic::waitForMessage<sensor_msgs::JointState>("/joint_states", ros::Duration(60)));
  const std::string config = configWith("controller: arm_controller/follow_joint_trajectory",
                                        "controller: arm_with_torso_controller/follow_joint_trajectory",
                                        "bad_controller_calibration_" + std::to_string(getpid()) + ".yaml");
  startNode("bad_controller", config, {});
  const std::string log = logWith(": ready (", 60);
  const std::string said = "arm.controller '/arm_with_torso_controller/follow_joint_trajectory' (" + config +
                           "): no action server after 3.0 s (the master knows the FollowJointTrajectory servers ";
  EXPECT_NE(log.find(said), std::string::npos) << log;
  EXPECT_NE(log.find("/arm_controller/follow_joint_trajectory"), std::string::npos) << log;
  std::printf("the node's start-up with a controller no server offers:\n%s\n", log.substr(log.find(said)).c_str());

  // A calibration fails on it, naming the action; the file from before stays as it was.
  imagenets_calibration_msgs::Calibrate srv;
  srv.request.redundancy = 1;
  ASSERT_TRUE(ros::service::waitForService(node_ + "/calibrate", 30000));
  ASSERT_TRUE(ros::service::call(node_ + "/calibrate", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("action server '/arm_with_torso_controller/follow_joint_trajectory' not available"),
            std::string::npos)
      << srv.response.message;
  std::printf("calibrate: %s\n", srv.response.message.c_str());
  EXPECT_EQ(readFile(file_), previous_);
  std::remove(config.c_str());
}

TEST_F(BadInput, AUrdfThatDoesNotParseNamesTheParameterAndTheParsersReason) {
  // /bad_urdf/robot_description (the .test sets it): cut short in the middle of a tag.
  startNode("bad_urdf", imagenets::packageFile("robot_description", "config/mobile_manipulator/calibration.yaml"),
            {"robot_description:=/bad_urdf/robot_description"});
  const int status = node_process_.exitStatus(60);
  const std::string log = readFile(log_);
  EXPECT_GT(status, 0) << log;
  EXPECT_NE(log.find("parameter /bad_urdf/robot_description: not a valid URDF: Failed to read Element name"), std::string::npos) << log;
  std::printf("the node's start-up with a URDF that does not parse:\n%s\n", log.c_str());
  EXPECT_EQ(readFile(file_), previous_);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "calibration_bad_input_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
