// rostest: friend_calibration_node started with a damaged calibration file (cut short, garbage,
// empty) says so, naming the file, publishes the NOMINAL fixed point and serves requests. The test
// starts the node itself, once per file, and reads what it prints (a message on /rosout sent while
// the node starts could be lost before its connection to this test is up).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets/testing/rostest_util.h"
#include "imagenets/package_file.h"
#include "files_and_processes.h"

namespace {

namespace fs = std::filesystem;

class DamagedCalibrationFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("friend_calibration_startup_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    good_ = readFile(fs::path(IMAGENETS_SOURCE_DIR) / "test/pth_fixed_point.yaml");
    ASSERT_NE(good_.find("\ncrc32: "), std::string::npos);
  }
  void TearDown() override {
    node_process_.stop();
    fs::remove_all(dir_);
  }

  // Starts the node on `content` as its calibration file; its output goes to a log file.
  void startNode(const std::string& name, const std::string& content) {
    file_ = (dir_ / (name + ".yaml")).string();
    std::ofstream(file_, std::ios::binary) << content;
    log_ = (dir_ / (name + ".log")).string();
    node_name_ = "/startup_" + name;
    // Line-buffered: the log holds the node's INFO lines (stdout) by the time it answers.
    node_process_.start({"stdbuf", "-oL", IMAGENETS_CALIBRATION_NODE, "__name:=" + node_name_.substr(1),
                         "_calibration_file:=" + file_, "_server_timeout:=1.0",
                         "_description:=" + imagenets::packageFile("friend_description", "config/robot.yaml"),
                         "_marker:=" + imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"),
                         "_net:=" + imagenets::packageFile("friend_calibration", "config/nets/calibration.yaml")},
                        log_);
    ASSERT_GT(node_process_.pid(), 0);
  }

  // The node's start-up: the error names the file and says the nominal frame is published; the
  // frame is the nominal one; the node answers a request.
  void expectNominalAndServing(const std::string& why) {
    std::string log;
    const bool said = waitFor(
        [&] {
          log = readFile(log_);
          return log.find(": ready (") != std::string::npos;
        },
        60.0);
    ASSERT_TRUE(said) << "the node did not start:\n" << log;
    EXPECT_NE(log.find("calibration file '" + file_ + "'"), std::string::npos) << log;
    EXPECT_NE(log.find(why), std::string::npos) << log;
    EXPECT_NE(log.find("publishing the nominal fixed point"), std::string::npos) << log;

    tf2_ros::Buffer buffer;
    tf2_ros::TransformListener listener(buffer);
    std::string error;
    ASSERT_TRUE(buffer.canTransform("base_link", "pth_fixed_point", ros::Time(0), ros::Duration(30.0), &error)) << error;
    ASSERT_TRUE(buffer.canTransform("base_link", "pth_fixed_point_nominal", ros::Time(0), ros::Duration(30.0), &error));
    const auto published = buffer.lookupTransform("base_link", "pth_fixed_point", ros::Time(0)).transform;
    const auto nominal = buffer.lookupTransform("base_link", "pth_fixed_point_nominal", ros::Time(0)).transform;
    EXPECT_DOUBLE_EQ(published.translation.x, nominal.translation.x);
    EXPECT_DOUBLE_EQ(published.translation.y, nominal.translation.y);
    EXPECT_DOUBLE_EQ(published.translation.z, nominal.translation.z);
    EXPECT_DOUBLE_EQ(published.rotation.w, nominal.rotation.w);

    imagenets_calibration_msgs::Calibrate srv;
    srv.request.redundancy = 2;  // refused at once: the node answers without a robot
    ASSERT_TRUE(ros::service::waitForService(node_name_ + "/calibrate", 30000));
    ASSERT_TRUE(ros::service::call(node_name_ + "/calibrate", srv));
    EXPECT_FALSE(srv.response.success);
    EXPECT_NE(srv.response.message.find("redundancy must be odd"), std::string::npos) << srv.response.message;
  }

  fs::path dir_;
  std::string good_, file_, log_, node_name_;
  ChildProcess node_process_;
};

TEST_F(DamagedCalibrationFile, CutShortBetweenTwoLines) {
  // Everything but the last line: the rest parses, only its CRC line is missing.
  const std::string body = good_.substr(0, good_.rfind("crc32: "));
  startNode("cut", body);
  expectNominalAndServing("incomplete");
}

TEST_F(DamagedCalibrationFile, CutInTheMiddle) {
  startNode("half", good_.substr(0, good_.size() / 2));
  expectNominalAndServing("calibration file");
}

TEST_F(DamagedCalibrationFile, Garbage) {
  startNode("garbage", good_.substr(0, 300) + "\x01\x02 {{[[ : : garbage" + good_.substr(340));
  expectNominalAndServing("corrupt");
}

TEST_F(DamagedCalibrationFile, Empty) {
  startNode("empty", "");
  expectNominalAndServing("empty");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_calibration_startup_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
