// rostest: a bag recorded with plain `rosbag record` while the mobile manipulator is moved by
// other means, then calibrated offline with `imagenets calibrate --bag` (see
// teleop_bag_calibration.test). The test program is the one moving the robot: 16 poses of a
// calibration plan of the nominal robot and one with the head turned away, each through the arm's
// and the head's FollowJointTrajectory controllers (the imagenets/FollowJointTrajectory block, as
// a teleoperation script would send goals), with a pause at each.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>

#include <boost/make_shared.hpp>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <ros/master.h>
#include <ros/network.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "friend_hw_sim/true_robot.h"
#include "imagenets/blocks/block_harness.h"
#include "imagenets/testing/command_runner.h"
#include "imagenets/testing/rostest_util.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/storage.h"

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr int kPoses = 16;
constexpr double kPause = 1.5;  // s standing at each pose: several stereo pairs at 3 Hz

std::string param(const std::string& name) {
  std::string value;
  EXPECT_TRUE(ros::NodeHandle("~").getParam(name, value)) << "the test's ~" << name << " is not set";
  return value;
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

// One group to `q` through its controller, as the calibration's own motion does.
void move(const std::string& action, const std::vector<std::string>& joints, const std::vector<double>& q) {
  auto target = boost::make_shared<sensor_msgs::JointState>();
  target->name = joints;
  target->position = q;
  imagenets::blocks::BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", action).set("max_velocity", 0.6).set("server_timeout", 30.0);
  h.input("configuration", target).run();
}

// Stops a node as `rosnode kill` does (its XML-RPC shutdown): rosbag record then closes the bag.
bool shutDown(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, true)) return false;
  std::string host, path;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return false;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  request[1] = "test done";
  return client.execute("shutdown", request, response);
}

TEST(TeleopBagCalibration, PlainRosbagRecordOfAMovedRobotCalibratesOffline) {
  const std::string description = param("description"), config = param("config"), urdf = param("urdf");
  const std::string dir = param("dir"), bag = param("bag"), recorder = param("recorder");
  ASSERT_EQ(mkdir(dir.c_str(), 0755), 0) << dir;
  const robot_description::RobotModel nominal(robot_description::loadRobotDescription(description));
  const auto& d = nominal.description();
  ASSERT_TRUE(ros::topic::waitForMessage<sensor_msgs::JointState>("/joint_states", ros::Duration(60)));
  // rosbag record writes BAG.active from its first message on.
  ASSERT_TRUE(waitFor([&] { return exists(bag + ".active"); }, 60)) << "rosbag record did not start " << bag;

  // The poses a user would pick (`imagenets calibration-plan --list`), then the head turned away.
  auto poses = imagenets_calibration::calibrationPoses(nominal, kPoses, "joint");
  ASSERT_EQ(poses.size(), static_cast<size_t>(kPoses));
  auto away = poses.back();
  const auto& pan = d.head.joints[0];
  away.head[0] = away.head[0] > 0.5 * (pan.min + pan.max) ? pan.min + 0.05 : pan.max - 0.05;
  poses.push_back(away);
  // The robot stands where it was while the recording starts: a still period of its own.
  ros::WallDuration(kPause).sleep();
  const ros::WallTime start = ros::WallTime::now();
  for (const auto& p : poses) {
    // Arm and head together, as the calibration moves them: one after the other, the arm standing
    // while the head starts would be a still period (a sample) of its own.
    std::string head_error, arm_error;
    auto moving = [&](const std::string& action, const std::vector<std::string>& joints,
                      const std::vector<double>& q, std::string& error) {
      try {
        move(action, joints, q);
      } catch (const std::exception& e) {
        error = e.what();
      }
    };
    std::thread head([&] { moving("head_controller/follow_joint_trajectory", d.head.names(), p.head, head_error); });
    moving("arm_controller/follow_joint_trajectory", d.arm.names(), p.arm, arm_error);
    head.join();
    ASSERT_EQ(arm_error + head_error, "");
    ros::WallDuration(kPause).sleep();
  }
  const double moving = (ros::WallTime::now() - start).toSec();
  ASSERT_TRUE(shutDown(recorder)) << "could not stop " << recorder;
  ASSERT_TRUE(waitFor([&] { return exists(bag) && !exists(bag + ".active"); }, 60)) << "no closed bag " << bag;

  // Offline, with a master that does not exist: the bag, the config and the URDF file.
  const std::string output = dir + "/head_fixed_point.yaml";
  const imagenets::testing::CommandResult result = imagenets::testing::runCommand(
      "ROS_MASTER_URI=http://127.0.0.1:9 " IMAGENETS_TOOL,
      "calibrate --bag " + bag + " --config " + config + " --urdf " + urdf + " --output " + output);
  const int status = result.status;
  const std::string& out = result.output;
  std::printf("%d poses moved in %.1f s; imagenets calibrate --bag %s --config %s --urdf %s:\n%s", kPoses + 1, moving,
              bag.c_str(), config.c_str(), urdf.c_str(), out.c_str());
  ASSERT_EQ(status, 0) << out;
  // One sample per still period: the start, the 16 poses and the turned-away one (the bag cannot
  // tell that no target is in view), and why the other images were not taken.
  const size_t periods = kPoses + 2;
  EXPECT_NE(out.find("bag: " + std::to_string(periods) + " samples (arm and head still"), std::string::npos) << out;
  EXPECT_NE(out.find("not used (one per period)"), std::string::npos) << out;
  EXPECT_NE(out.find("while joints moved"), std::string::npos) << out;

  const auto r = imagenets_calibration::loadCalibration(output).result;
  ASSERT_EQ(r.samples.size(), periods);
  // The samples in the order the robot stood; the last one saw no target and is rejected.
  for (size_t k = 0; k < poses.size(); ++k) {
    for (size_t j = 0; j < poses[k].head.size(); ++j) EXPECT_NEAR(r.samples[k + 1].head_q[j], poses[k].head[j], 0.02) << k;
  }
  EXPECT_FALSE(r.samples.back().left.found);
  EXPECT_FALSE(r.samples.back().right.found);
  EXPECT_NE(std::find(r.rejected.begin(), r.rejected.end(), kPoses + 1), r.rejected.end());
  EXPECT_GE(static_cast<int>(r.used.size()), kPoses - 1) << out;

  // Against the simulator's truth, as the live rostests measure it.
  std::string error_file;
  ASSERT_TRUE(ros::param::get("/friend_sim/true_error", error_file));
  const auto truth = friend_hw_sim::loadTrueError(error_file, d, -1);
  const Eigen::Isometry3d identifiable = friend_hw_sim::identifiableHeadBase(d, truth);
  const double mm = 1000 * (r.fixed_point.translation() - identifiable.translation()).norm();
  const double deg = imagenets_calibration::angleBetween(r.fixed_point, identifiable) / kDeg;
  const double bound_mm = 3000 * r.sigmaTranslation(), bound_deg = 3 * r.sigmaRotation() / kDeg;
  std::printf("teleoperation bag (plain rosbag record), offline: error vs identifiable fixed point %.3f mm / %.4f deg; "
              "reported 3 sigma %.3f mm / %.4f deg; %zu of %zu samples used\n",
              mm, deg, bound_mm, bound_deg, r.used.size(), r.samples.size());
  EXPECT_LT(mm, 0.5);
  EXPECT_LT(deg, 0.05);
  EXPECT_LT(mm, bound_mm);
  EXPECT_LT(deg, bound_deg);
  if (!HasFailure()) std::remove(bag.c_str());  // 190 MB of images; kept to look at when it failed
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "teleop_bag_calibration_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
