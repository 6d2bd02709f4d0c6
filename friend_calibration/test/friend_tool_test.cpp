// The FRIEND calibration's commands (imagenets-NAME programs) through the `imagenets` tool, run as
// a user runs them, in this package's folder.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <vector>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include "imagenets/testing/command_runner.h"
#include "imagenets/testing/read_file.h"
#include "imagenets_calibration/bag_recorder.h"

namespace {

using imagenets::testing::expectContains;
using imagenets::testing::readFile;
using imagenets::testing::tempPath;
using imagenets::testing::tool;  // `imagenets ARGS`, run in this package's folder
using Result = imagenets::testing::CommandResult;

}  // namespace

// --set-all gives every block of the net and its sub-nets that has the property one value: here the
// robot description, so `run` replays the stored samples of a six-axis robot's calibration
// (test/six_axis_calibration.yaml, written by the calibration node on robot_description's six_axis in
// the simulator) with that robot's kinematics, and finds the stored fixed point again.
TEST(Tool, RunSetAllGivesEveryBlockOfTheNetTreeTheRobotDescription) {
  const std::string dir = tempPath("six_axis_replay");
  const std::string replay = "run config/nets/calibration.yaml --set samples.net=$(rospack find imagenets_calibration)/config/nets/calibration_sample_replay.yaml "
                             "--set plan.replay=" +
                             boost::filesystem::absolute("test/six_axis_calibration.yaml").string() +
                             " --set plan.method=joint ";
  Result r = tool(replay + "--set-all description=$(rospack find robot_description)/config/six_axis/robot.yaml --output-dir " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "--set-all description: plan samples/until/solve solve");
  const std::string fixed = readFile(dir + "/fixed_point.value.yaml");
  expectContains(fixed, "x: -0.08977030358");  // the stored fixed_point: [-0.089770303580141764, ...
  expectContains(fixed, "z: 1.28800168702");
  // Without it the blocks compute with the net's robot (FRIEND's 7-joint arm).
  r = tool(replay);
  EXPECT_EQ(r.status, 1);
  expectContains(r.output, "expected 7 joint angles, got 6");
}

TEST(Tool, StudyCommandsListTheirFlagsWithDefaults) {
  Result r = tool("accuracy-study --help", true);
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char* flag : {"--true-robots arg (=20)", "--first-seed arg (=1)", "--magnitude arg (=1)", "--reflections arg",
                           "--method arg (=joint)", "--loops arg (=5)", "--pose-sweep arg (=3,7)",
                           "--output-dir arg (=out/accuracy)", "--wait arg (=60)"}) {
    expectContains(r.output, flag);
  }
  r = tool("repeatability --help", true);
  for (const char* flag : {"--runs arg (=100)", "--redundancy arg (=1,3,5)", "--method arg (=both)",
                           "--real-speed-runs arg (=2)", "--output-dir arg (=out/repeatability)"}) {
    expectContains(r.output, flag);
  }
  r = tool("calibrate --help", true);
  for (const char* flag : {"--redundancy arg (=5)", "--bag arg", "--config arg", "--set arg", "-o [ --output ] arg"}) {
    expectContains(r.output, flag);
  }
  // roslaunch's own arguments are no flags of the command; anything else unknown is named.
  r = tool("accuracy-study --loops 4 __name:=study __log:=/tmp/study.log");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--loops must be odd and >= 1, not 4");
  r = tool("calibrate --bags x.bag");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "imagenets calibrate: unknown option '--bags'");
}

TEST(Tool, StudyCommandsCheckTheirArgumentsFirst) {
  Result r = tool("repeatability --redundancy 1,x");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--redundancy '1,x': 'x' is not a count");
  // Checked before anything connects to ROS.
  r = tool("repeatability --real-speed-runs -1");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--real-speed-runs must be >= 0");
  expectContains(r.output, "usage: imagenets repeatability");
  r = tool("accuracy-study --magnitude 0");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--magnitude must be positive");
  expectContains(r.output, "usage: imagenets accuracy-study");
  r = tool("accuracy-study --reflections 150");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--reflections is a percentage 0..100");
  r = tool("accuracy-study --pose-sweep 1,x");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--pose-sweep '1,x': 'x' is not a count");
  r = tool("accuracy-study --loops 4");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--loops must be odd and >= 1, not 4");
  r = tool("accuracy-study --first-seed 0");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--first-seed must be >= 1");
}

TEST(Tool, CalibrationPlanNamesWhatItsPosesLeaveUnobservable) {
  // One loop of the joint method (2 poses): one relative motion, so the marker's rotation about
  // its axis and with it the fixed point are left to the priors.
  Result r = tool("calibration-plan --description $(rospack find friend_description)/config/robot.yaml --poses 2", true);
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "calibration plan: method joint, 2 poses");
  expectContains(r.output, "not observable from these poses (posterior std > 0.5 x prior): fixed point x");
  expectContains(r.output, "marker offset rz");
  // The default plan (5 loops x 2 poses) determines every estimated parameter.
  r = tool("calibration-plan --description $(rospack find friend_description)/config/robot.yaml --list", true);
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "method joint, 10 poses");
  expectContains(r.output, "pose  9: arm [");
  expectContains(r.output, "every estimated parameter observable");
  r = tool("calibration-plan --description $(rospack find friend_description)/config/robot.yaml --noise 0");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--noise must be positive");
  // With the mobile manipulator's mono camera (--camera) instead of its stereo pair.
  r = tool("calibration-plan --description $(rospack find robot_description)/config/mobile_manipulator/robot.yaml "
           "--camera mono --poses 30", true);
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "method joint, 30 poses, mono camera");
  expectContains(r.output, "every estimated parameter observable");
  r = tool("calibration-plan --description $(rospack find robot_description)/config/six_axis/robot.yaml --camera mono");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--camera: 'mono', but ");
  expectContains(r.output, "gives the head no mono camera (head.mono_camera)");
}

TEST(Tool, HelpListsThePackagesCommands) {
  const Result r = tool("--help", true);
  EXPECT_EQ(r.status, 0);
  for (const char* known : {"calibrate", "repeatability", "accuracy-study", "calibration-plan"}) {
    expectContains(r.output, std::string("  ") + known + " ");
  }
}

// `calibrate --bag` with a bag that lacks the cameras: the error names the missing topic (and what
// the bag has), with no master needed, and the output file of a previous calibration stays as it was.
TEST(Tool, CalibrateFromABagWithoutTheNeededTopicsNamesTheTopicAndKeepsTheOutput) {
  const std::string dir = tempPath("calibrate_bag");
  boost::filesystem::create_directories(dir);
  const std::string bag = dir + "/joints_only.bag";
  {
    imagenets_calibration::BagRecorder recorder(bag);
    sensor_msgs::JointState js;
    js.header.stamp = ros::Time(1);
    js.name = {"arm_joint_1"};
    js.position = {0.1};
    recorder.write("/joint_states", js.header.stamp, js);
    recorder.commit();
  }
  const std::string output = dir + "/previous.yaml";
  std::ofstream(output) << "a previous calibration\n";
  Result r = tool("calibrate --bag " + bag + " --config $(rospack find friend_description)/config/robot.yaml --output " +
                  output);
  EXPECT_EQ(r.status, 1) << r.output;
  expectContains(r.output, "no topic '/stereo/left/image_raw' (the left camera's images); the bag has /joint_states");
  expectContains(r.output, output + " is unchanged");
  EXPECT_EQ(readFile(output), "a previous calibration\n");
  // --bag needs the robot's description; the offline options go with --bag only.
  r = tool("calibrate --bag " + bag);
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "--bag needs --config FILE");
  r = tool("calibrate --output " + output);
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "go with --bag");
}
