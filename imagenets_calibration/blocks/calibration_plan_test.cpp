#include <set>

#include <gtest/gtest.h>
#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <ros/package.h>
#include <std_msgs/Int32.h>

#include "imagenets_calibration/bundle_adjustment.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets/blocks/block_harness.h"
#include "imagenets/package_file.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;
using namespace imagenets_calibration;

namespace {
RobotModel nominal() { return RobotModel(robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath())); }
}  // namespace

TEST(CalibrationPlan, JointMethodVisitsTheLibrarysPosesPerLoop) {
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("method", std::string("joint")).set("loops", 3).set("poses_per_loop", 2);
  h.run();
  const auto plan = h.output<imagenets_calibration_msgs::CalibrationPlan>("plan");
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->samples, 6);
  EXPECT_EQ(h.output<std_msgs::Int32>("samples")->data, 6);
  const auto poses = calibrationPoses(nominal(), 6, "joint");
  ASSERT_EQ(plan->arm.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(plan->arm[k].position, poses[k].arm);
    EXPECT_EQ(plan->head[k].position, poses[k].head);
    EXPECT_EQ(plan->arm_approach[k].position, poses[k].arm);  // no re-approach
    EXPECT_EQ(plan->arm[k].name, nominal().description().arm.names());
  }
}

TEST(CalibrationPlan, PaperMethodReapproachesTheSamePoseAndNeedsOddLoops) {
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("method", std::string("paper")).set("loops", 3);
  h.run();
  const auto plan = h.output<imagenets_calibration_msgs::CalibrationPlan>("plan");
  EXPECT_EQ(plan->samples, 3);
  EXPECT_EQ(plan->arm[0].position, plan->arm[2].position);
  EXPECT_NEAR(plan->arm[1].position[3] - plan->arm_approach[1].position[3], 10 * M_PI / 180, 1e-12);
  BlockHarness even("imagenets/CalibrationPlan");
  even.set("description", robot_description::exampleRobotDescriptionPath());
  even.set("loops", 4);
  EXPECT_NE(even.runError().find("property 'loops': redundancy must be odd"), std::string::npos);
}

TEST(CalibrationPlan, AReplayPlanCountsTheStoredSamplesAndNamesABadFile) {
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("replay", std::string("/nonexistent/pth_fixed_point.yaml"));
  const std::string error = h.runError();
  EXPECT_NE(error.find("property 'replay'"), std::string::npos) << error;
  EXPECT_NE(error.find("/nonexistent/pth_fixed_point.yaml"), std::string::npos) << error;
}

TEST(CalibrationPlan, ThePosesPropertyGivesThatManySamplesWhateverTheLoops) {
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("method", std::string("joint")).set("loops", 5).set("poses_per_loop", 2).set("poses", 7);
  h.run();
  const auto plan = h.output<imagenets_calibration_msgs::CalibrationPlan>("plan");
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->samples, 7);
  EXPECT_EQ(h.output<std_msgs::Int32>("samples")->data, 7);
  ASSERT_EQ(plan->arm.size(), 7u);
  const auto poses = calibrationPoses(nominal(), 7, "joint");
  for (size_t k = 0; k < 7; ++k) EXPECT_EQ(plan->arm[k].position, poses[k].arm);
  // 0: the loops decide (5 x 2).
  BlockHarness loops("imagenets/CalibrationPlan");
  loops.set("description", robot_description::exampleRobotDescriptionPath());
  loops.set("method", std::string("joint")).set("loops", 5).set("poses_per_loop", 2).set("poses", 0);
  loops.run();
  EXPECT_EQ(loops.output<imagenets_calibration_msgs::CalibrationPlan>("plan")->samples, 10);
  // The paper method's median needs an odd count.
  BlockHarness paper("imagenets/CalibrationPlan");
  paper.set("description", robot_description::exampleRobotDescriptionPath());
  paper.set("method", std::string("paper")).set("poses", 4);
  EXPECT_NE(paper.runError().find("property 'poses': the paper method's samples must be odd"), std::string::npos);
}

TEST(CalibrationPlan, AnUncertaintyTargetPlansTheNextPosesUpToMaxPoses) {
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("method", std::string("joint")).set("poses", 6).set("target_uncertainty", 0.0004).set("max_poses", 14);
  h.run();
  const auto plan = h.output<imagenets_calibration_msgs::CalibrationPlan>("plan");
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->samples, 6);  // taken in any case
  EXPECT_EQ(plan->max_samples, 14);
  EXPECT_EQ(plan->target_uncertainty, 0.0004);
  EXPECT_EQ(h.output<std_msgs::Int32>("samples")->data, 6);
  EXPECT_EQ(h.output<std_msgs::Int32>("max_samples")->data, 14);
  // The poses added are the ones a 14-pose plan takes after its first six.
  ASSERT_EQ(plan->arm.size(), 14u);
  const auto poses = calibrationPoses(nominal(), 14, "joint");
  const auto six = calibrationPoses(nominal(), 6, "joint");
  for (size_t k = 0; k < 14; ++k) EXPECT_EQ(plan->arm[k].position, poses[k].arm);
  for (size_t k = 0; k < 6; ++k) EXPECT_EQ(six[k].arm, poses[k].arm);
  // Without a target max_poses does not matter.
  BlockHarness off("imagenets/CalibrationPlan");
  off.set("description", robot_description::exampleRobotDescriptionPath());
  off.set("method", std::string("joint")).set("poses", 6).set("max_poses", 14);
  off.run();
  EXPECT_EQ(off.output<imagenets_calibration_msgs::CalibrationPlan>("plan")->max_samples, 6);
  EXPECT_EQ(off.output<imagenets_calibration_msgs::CalibrationPlan>("plan")->arm.size(), 6u);
  // Named errors: a maximum below the poses asked for; the paper method (no covariance).
  BlockHarness below("imagenets/CalibrationPlan");
  below.set("description", robot_description::exampleRobotDescriptionPath());
  below.set("method", std::string("joint")).set("poses", 6).set("target_uncertainty_rotation", 0.001).set("max_poses", 4);
  EXPECT_NE(below.runError().find("property 'max_poses': 4 is below the 6 poses"), std::string::npos);
  BlockHarness paper("imagenets/CalibrationPlan");
  paper.set("description", robot_description::exampleRobotDescriptionPath());
  paper.set("method", std::string("paper")).set("loops", 3).set("target_uncertainty", 0.001);
  EXPECT_NE(paper.runError().find("property 'target_uncertainty': an uncertainty target needs the joint method"),
            std::string::npos);
}

// A camera on a stand cannot turn: the plan's arm carries the target across its image (the centre
// and towards each corner), every pose another one, the head's target always empty.
TEST(CalibrationPlan, ACameraOnAStandSeesTheTargetCarriedAcrossItsImage) {
  const RobotModel model(robot_description::loadRobotDescription(ros::package::getPath("robot_description") +
                                                                 "/config/ur_stand/robot.yaml"));
  std::string why;
  const auto cameras = stereoCamerasOf(model.description(), &why);
  ASSERT_TRUE(cameras) << why;
  const auto poses = calibrationPoses(model, 30, "joint");
  ASSERT_EQ(poses.size(), 30u);
  std::set<std::pair<int, int>> cells;  // image thirds the target's centre falls in
  double min_u = 1e9, max_u = -1e9, min_v = 1e9, max_v = -1e9;
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_TRUE(poses[k].head.empty());
    EXPECT_TRUE(model.description().arm.limitViolation(poses[k].arm).empty()) << "pose " << k;
    for (size_t j = 0; j < k; ++j) EXPECT_NE(poses[k].arm, poses[j].arm) << "poses " << j << " and " << k;
    const Eigen::Vector3d c = model.leftCamera({}).inverse() * model.marker(poses[k].arm).translation();
    ASSERT_GT(c.z(), 0.5) << "pose " << k;
    const Eigen::Vector2d uv = cameras->left.project(c);
    min_u = std::min(min_u, uv.x()), max_u = std::max(max_u, uv.x());
    min_v = std::min(min_v, uv.y()), max_v = std::max(max_v, uv.y());
    cells.insert({static_cast<int>(3 * uv.x() / 1024), static_cast<int>(3 * uv.y() / 768)});
  }
  EXPECT_GE(cells.size(), 5u) << "the target's centre in " << cells.size() << " of the image's 9 thirds";
  EXPECT_GT(max_u - min_u, 300) << min_u << " .. " << max_u << " px";
  EXPECT_GT(max_v - min_v, 200) << min_v << " .. " << max_v << " px";
}

TEST(CalibrationPlan, PlansForTheCameraItsCalibrationCameraNames) {
  // The mobile manipulator's mono camera has another field of view than its stereo pair: the
  // head looks past the target by a fraction of that camera's, so the poses differ.
  const std::string path = imagenets::packageFile("robot_description", "config/mobile_manipulator/robot.yaml");
  const auto d = robot_description::loadRobotDescription(path);
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", path).set("method", std::string("joint")).set("poses", 6);
  h.set("calibration_camera", std::string("mono"));
  h.run();
  const auto plan = h.output<imagenets_calibration_msgs::CalibrationPlan>("plan");
  ASSERT_TRUE(plan);
  const auto mono = calibrationPoses(RobotModel(robot_description::withCalibrationCamera(d, "mono", "test")), 6, "joint");
  const auto stereo = calibrationPoses(RobotModel(d), 6, "joint");
  bool differ = false;
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(plan->head[k].position, mono[k].head);
    EXPECT_EQ(plan->arm[k].position, mono[k].arm);
    differ |= mono[k].head != stereo[k].head;
  }
  EXPECT_TRUE(differ);
  h.set("calibration_camera", std::string("both"));
  EXPECT_NE(h.runError().find("property 'calibration_camera': 'both' is no calibration camera"), std::string::npos);
}
