// The calibration with one camera: the mobile manipulator (robot_description's
// config/mobile_manipulator) measured with its head's mono camera alone. Samples are made from a
// known true robot (head mount, target offset and joint zero offsets off the drawing) as the mono
// camera sees its target at planned poses; the chain and the pixel-level bundle adjustment must
// find that truth without any stereo observation.
#include <gtest/gtest.h>

#include "imagenets/package_file.h"
#include "imagenets_calibration/bundle_adjustment.h"
#include "imagenets_calibration/calibration.h"

namespace imagenets_calibration {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d xyzRpy(double x, double y, double z, double r, double p, double yaw) {
  return robot_description::fromXyzRpy(Eigen::Vector3d(x, y, z), Eigen::Vector3d(r, p, yaw) * kDeg);
}

struct MonoCamera : ::testing::Test {
  robot_description::RobotDescription stereo_description = robot_description::loadRobotDescription(
      imagenets::packageFile("robot_description", "config/mobile_manipulator/robot.yaml"));
  RobotModel model{robot_description::withCalibrationCamera(stereo_description, "mono", "test")};
  CameraModels cameras = *cameraModelsOf(model.description(), nullptr);

  // The true robot: head mount 12 mm / 1.8 deg off, the target 0.9 mm / 0.36 deg off its drawing,
  // zero offsets on an arm joint and on the tilt (both estimated by the joint method).
  Eigen::Isometry3d true_head = model.headBase() * xyzRpy(0.008, -0.006, 0.007, 0.9, -1.2, 1.0);
  Eigen::Isometry3d true_marker = model.description().marker.pose * xyzRpy(-0.0005, 0.0008, 0, 0.3, -0.2, 0);
  std::vector<double> true_arm_offsets{0, 0.04 * kDeg, 0, -0.05 * kDeg, 0, 0, 0};
  std::vector<double> true_head_offsets{0, 0.08 * kDeg};

  RobotModel truth() const {
    auto d = withJointOffsets(model, true_arm_offsets, true_head_offsets).description();
    d.head.mount = true_head;
    d.marker.pose = true_marker;
    return RobotModel(d);
  }

  // What the mono camera sees at `pose` on the true robot: its target's 8 defined points
  // (distorted pixels, exact) and their pose; the stereo pair's observations are left wrong and
  // "found", so that using them would show.
  Sample sampleAt(const RobotModel& t, const CalibrationPose& pose) const {
    Sample s;
    s.arm_q = pose.arm;
    s.head_q = pose.head;
    MarkerObservation& o = s.mono;
    o.found = true;
    o.reprojection_error = 0.01;
    o.pose = t.monoCamera(pose.head).inverse() * t.marker(pose.arm);
    for (const auto& p : markerDefinedPoints(model.description().marker_size)) {
      o.points.push_back(cameras.cameras.front().model.project(o.pose * p));
    }
    s.left = s.right = o;
    s.left.pose.translation().x() += 0.05;
    s.right.pose.translation().y() -= 0.05;
    return s;
  }
};

TEST_F(MonoCamera, TheCameraModelsAreTheMonoCameraAlone) {
  ASSERT_EQ(cameras.cameras.size(), 1u);
  const CalibrationCamera& c = cameras.cameras.front();
  EXPECT_EQ(c.observation, Sample::kMono);
  EXPECT_EQ(c.width, 1280);  // head_camera_rgb.yaml, not the stereo pair's 1024 x 768
  EXPECT_EQ(c.height, 960);
  EXPECT_DOUBLE_EQ(c.model.K(0, 0), 1250.0);
  const std::vector<double> head{0.2, 0.1};
  EXPECT_TRUE(c.pose(model.description().head.end(head)).isApprox(model.monoCamera(head), 1e-12));
  // The stereo description keeps the pair.
  const auto pair = cameraModelsOf(stereo_description, nullptr);
  ASSERT_TRUE(pair);
  ASSERT_EQ(pair->cameras.size(), 2u);
  EXPECT_EQ(pair->cameras[1].observation, Sample::kRight);
  const Eigen::Isometry3d right = pair->cameras[1].pose(stereo_description.head.end(head));
  EXPECT_TRUE(right.isApprox(RobotModel(stereo_description).rightCamera(head), 1e-12));
}

TEST_F(MonoCamera, TheChainUsesTheMonoDetectionAndNamesItWhenMissing) {
  const RobotModel t = truth();
  Sample s = sampleAt(t, {model.description().arm_calibration_pose, model.description().head_calibration_pose});
  solveSample(model, s, FusionLimits());
  ASSERT_TRUE(s.valid) << s.reason;
  EXPECT_EQ(s.fusion, "mono");
  EXPECT_TRUE(s.marker_in_left.isApprox(s.mono.pose, 1e-12));
  s.mono.found = false;
  s.mono.reason = "no tag";
  solveSample(model, s, FusionLimits());
  EXPECT_FALSE(s.valid);
  EXPECT_EQ(s.reason, "marker not found (mono: no tag)");
}

TEST_F(MonoCamera, TheJointMethodAtPixelLevelFindsTheTruthFromOneCamera) {
  const RobotModel t = truth();
  const auto poses = calibrationPoses(model, 20, "joint");
  std::vector<Sample> samples;
  for (const auto& p : poses) samples.push_back(sampleAt(t, p));
  const Result r = calibrate(model, samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.used.size(), poses.size()) << r.message;
  EXPECT_NE(r.message.find("pixel-level bundle adjustment of 20 detections"), std::string::npos) << r.message;
  for (const Sample& s : r.samples) EXPECT_EQ(s.fusion, "mono");
  const double mm = 1000 * (r.fixed_point.translation() - true_head.translation()).norm();
  const double deg = angleBetween(r.fixed_point, true_head) / kDeg;
  std::printf("mono camera, exact points, 20 poses: fixed point error %.5f mm / %.6f deg, target offset %.5f mm; 3 sigma "
              "%.4f mm / %.5f deg\n",
              mm, deg, 1000 * (r.marker_offset.translation() - true_marker.translation()).norm(),
              3000 * r.sigmaTranslation(), 3 * r.sigmaRotation() / kDeg);
  EXPECT_LT(mm, 0.01);
  EXPECT_LT(deg, 0.001);
  EXPECT_NEAR(r.head_joint_offsets[1], true_head_offsets[1], 1e-5);
  EXPECT_NEAR(r.arm_joint_offsets[3], true_arm_offsets[3], 1e-5);
  EXPECT_TRUE(r.has_covariance);
  EXPECT_TRUE(r.unobservable.empty()) << r.message;
  // The same samples solved as a stereo pair use the wrong left/right detections: far off.
  const Result as_stereo = calibrate(RobotModel(stereo_description), samples, "joint", FusionLimits(), CombineOptions());
  EXPECT_TRUE(!as_stereo.success || (as_stereo.fixed_point.translation() - true_head.translation()).norm() > 0.005);
}

TEST_F(MonoCamera, ADescriptionWithoutTheMonoCamerasFileSaysSo) {
  auto d = model.description();
  d.mono_camera_info = "/nonexistent/head_camera_rgb.yaml";
  std::string why;
  EXPECT_FALSE(cameraModelsOf(d, &why));
  EXPECT_NE(why.find("/nonexistent/head_camera_rgb.yaml"), std::string::npos) << why;
}

}  // namespace
}  // namespace imagenets_calibration
