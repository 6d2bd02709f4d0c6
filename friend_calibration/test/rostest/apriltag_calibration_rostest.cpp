// rostest: the simulated FRIEND carries an AprilTag (a target file) instead of the square marker;
// the calibration node, given the same file, measures every sample with the AprilTag detection net
// (its sample net's imagenets/TargetDetectionNet) and finds the true fixed point from the tag's
// corners at pixel level. A bad target file is named in every answer of a node given it.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "friend_hw_sim/true_robot.h"
#include "imagenets/vision/frames.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/storage.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets/package_file.h"

namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(AprilTagCalibration, TheJointMethodFindsTheFixedPointFromTheTagsCorners) {
  ASSERT_TRUE(ros::service::waitForService("/friend_calibration/calibrate", ros::Duration(60)));
  imagenets_calibration_msgs::Calibrate srv;
  srv.request.redundancy = 5;
  srv.request.method = "joint";
  ASSERT_TRUE(ros::service::call("/friend_calibration/calibrate", srv));
  const auto& res = srv.response;
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.samples_used + res.samples_rejected, 10);
  EXPECT_GE(res.samples_used, 9) << res.message;
  EXPECT_TRUE(res.unobservable.empty()) << res.message;
  EXPECT_NE(res.message.find("pixel-level bundle adjustment"), std::string::npos) << res.message;

  // Every sample was measured on the tag: 4 corners with ids 0..3 and their points on the tag.
  const auto stored = imagenets_calibration::loadCalibration(res.file);
  int observations = 0;
  for (const auto& s : stored.result.samples) {
    for (const auto* o : {&s.left, &s.right}) {
      if (!o->found) continue;
      ++observations;
      ASSERT_EQ(o->points.size(), 4u);
      EXPECT_EQ(o->point_ids, (std::vector<int>{0, 1, 2, 3}));
      ASSERT_EQ(o->object_points.size(), 4u);
      EXPECT_NEAR(o->object_points[1].x(), 0.03, 1e-9);  // top-right corner of the 60 mm tag
      EXPECT_NEAR(o->object_points[1].y(), 0.03, 1e-9);
    }
  }
  EXPECT_GE(observations, 18);

  // Against the simulator's truth (true_error.yaml): the effective fixed point (pan offset folded
  // in) and the identifiable one (arm joint 1's too), as the square marker's rostest measures it.
  const robot_description::RobotModel nominal(
      robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml")));
  std::string error_file;
  ASSERT_TRUE(ros::param::get("/friend_sim/true_error", error_file));
  const auto truth = friend_hw_sim::loadTrueError(error_file, nominal.description(), -1);
  const Eigen::Isometry3d x = imagenets::frames::toIsometry(res.fixed_point.transform, "fixed point");
  const Eigen::Isometry3d effective = friend_hw_sim::effectiveHeadBase(nominal.description(), truth);
  const Eigen::Isometry3d identifiable = friend_hw_sim::identifiableHeadBase(nominal.description(), truth);
  const double eff_mm = 1000 * (x.translation() - effective.translation()).norm();
  const double eff_deg = imagenets_calibration::angleBetween(x, effective) / kDeg;
  const double id_mm = 1000 * (x.translation() - identifiable.translation()).norm();
  const double id_deg = imagenets_calibration::angleBetween(x, identifiable) / kDeg;
  const auto& c = res.fixed_point_covariance;
  const double bound_mm = 3000 * std::sqrt(c[0] + c[7] + c[14]), bound_deg = 3 * std::sqrt(c[21] + c[28] + c[35]) / kDeg;
  std::printf("AprilTag on the gripper: error vs effective fixed point %.3f mm / %.4f deg, vs identifiable %.3f mm / "
              "%.4f deg; reported 3 sigma %.3f mm / %.4f deg; %d of %d samples used; %.3f s compute, %.2f s total\n",
              eff_mm, eff_deg, id_mm, id_deg, bound_mm, bound_deg, res.samples_used,
              res.samples_used + res.samples_rejected, res.compute_time, res.total_time);
  // The accuracy one calibration must reach (0.5 mm / 0.05 deg), as the square marker does.
  EXPECT_LT(id_mm, 0.5);
  EXPECT_LT(id_deg, 0.05);
  EXPECT_LT(eff_mm, 0.5);
  EXPECT_LT(eff_deg, 0.1);
  EXPECT_LT(id_mm, bound_mm);
}

TEST(AprilTagCalibration, ABadTargetFileIsNamedInTheAnswer) {
  ASSERT_TRUE(ros::service::waitForService("/friend_calibration_bad_target/calibrate", ros::Duration(60)));
  imagenets_calibration_msgs::Calibrate srv;
  srv.request.redundancy = 3;
  ASSERT_TRUE(ros::service::call("/friend_calibration_bad_target/calibrate", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("bad_target.yaml: 'id': 31 out of range: family tag16h5 has ids 0..29"),
            std::string::npos)
      << srv.response.message;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "apriltag_calibration_rostest");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
