// The frame maths against hand-computed cases.
#include <cmath>

#include <gtest/gtest.h>

#include "imagenets/vision/frames.h"

using namespace imagenets::frames;

namespace {

Eigen::Quaterniond aboutAxis(double angle, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

Eigen::Isometry3d pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = q.toRotationMatrix();
  p.translation() = t;
  return p;
}

}  // namespace

TEST(FrameMaths, PoseConversionRoundTrip) {
  geometry_msgs::Pose p;
  p.position.x = 1;
  p.position.y = -2;
  p.position.z = 0.5;
  // 90 degrees about z: (x, y, z, w) = (0, 0, sin 45, cos 45).
  p.orientation.z = std::sqrt(0.5);
  p.orientation.w = std::sqrt(0.5);
  Eigen::Isometry3d t = toIsometry(p, "pose");
  EXPECT_NEAR((t * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, -1, 0.5)).norm(), 0, 1e-12);
  geometry_msgs::Pose back = toPose(t);
  EXPECT_NEAR(back.orientation.z, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(back.position.y, -2, 1e-12);
}

TEST(FrameMaths, RejectsNaNAndNonUnitQuaternions) {
  geometry_msgs::Pose p;
  p.orientation.w = 1;
  p.position.y = std::nan("");
  try {
    toIsometry(p, "input 'a'");
    FAIL() << "NaN accepted";
  } catch (const FrameError& e) {
    EXPECT_NE(std::string(e.what()).find("input 'a': position.y"), std::string::npos) << e.what();
  }
  p.position.y = 0;
  p.orientation.w = 2;
  try {
    toIsometry(p, "input 'a'");
    FAIL() << "non-unit quaternion accepted";
  } catch (const FrameError& e) {
    EXPECT_NE(std::string(e.what()).find("norm 2"), std::string::npos) << e.what();
  }
  // A rounding-size deviation is normalised, not rejected.
  p.orientation.w = 1.0005;
  EXPECT_NEAR(Eigen::Quaterniond(toIsometry(p, "a").rotation()).w(), 1.0, 1e-12);
}

TEST(FrameMaths, ComposeAndInvertHandComputed) {
  // a: translate (1,0,0), rotate 90 deg about z. b: translate (0,2,0).
  Eigen::Isometry3d a = pose({1, 0, 0}, aboutAxis(M_PI / 2, Eigen::Vector3d::UnitZ()));
  Eigen::Isometry3d b = pose({0, 2, 0}, Eigen::Quaterniond::Identity());
  // a*b maps the origin of b to a's rotation of (0,2,0) = (-2,0,0), plus (1,0,0).
  EXPECT_NEAR(((a * b).translation() - Eigen::Vector3d(-1, 0, 0)).norm(), 0, 1e-12);
  // inverse of a: rotation -90 about z, translation -R^T t = -(0,-1,0)... R^T (1,0,0) = (0,-1,0).
  EXPECT_NEAR((a.inverse().translation() - Eigen::Vector3d(0, 1, 0)).norm(), 0, 1e-12);
}

TEST(FrameMaths, MeanRotationOfSymmetricSetIsTheMiddle) {
  const Eigen::Vector3d axis(1, 2, 3);
  std::vector<Eigen::Quaterniond> qs{aboutAxis(0.1, axis), aboutAxis(0.2, axis), aboutAxis(0.3, axis)};
  EXPECT_NEAR(rotationAngle(meanRotation(qs), aboutAxis(0.2, axis)), 0, 1e-9);
}

TEST(FrameMaths, MeanRotationIgnoresQuaternionSigns) {
  // +-20 degrees about x; the second given as its antipode. Component means would give a
  // quaternion near zero (or a wrong axis); the eigenvector method gives the identity.
  Eigen::Quaterniond plus = aboutAxis(0.35, Eigen::Vector3d::UnitX());
  Eigen::Quaterniond minus = aboutAxis(-0.35, Eigen::Vector3d::UnitX());
  Eigen::Quaterniond minus_antipode(-minus.w(), -minus.x(), -minus.y(), -minus.z());
  const Eigen::Quaterniond mean = meanRotation({plus, minus_antipode});
  EXPECT_NEAR(rotationAngle(mean, Eigen::Quaterniond::Identity()), 0, 1e-9);
  EXPECT_GE(mean.w(), 0);
  // All given as antipodes: the same rotation comes out.
  Eigen::Quaterniond q = aboutAxis(1.0, Eigen::Vector3d(0, 1, 1));
  Eigen::Quaterniond q_antipode(-q.w(), -q.x(), -q.y(), -q.z());
  EXPECT_NEAR(rotationAngle(meanRotation({q, q_antipode, q}), q), 0, 1e-9);
}

TEST(FrameMaths, WeightedMeanRotationAndErrors) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  // Weight 0 on an outlier removes it.
  Eigen::Quaterniond m = meanRotation({aboutAxis(0.5, z), aboutAxis(2.5, z)}, {1.0, 0.0});
  EXPECT_NEAR(rotationAngle(m, aboutAxis(0.5, z)), 0, 1e-9);
  EXPECT_THROW(meanRotation({}), FrameError);
  EXPECT_THROW(meanRotation({m}, {1.0, 2.0}), FrameError);
  EXPECT_THROW(meanRotation({m}, {-1.0}), FrameError);
}

TEST(FrameMaths, PerAxisMedianResistsOutliers) {
  std::vector<Eigen::Vector3d> t{{1, 10, -1}, {2, 20, -2}, {3, 1000, -3}, {100, 30, -4}, {-50, 40, 500}};
  EXPECT_EQ(medianTranslation(t), Eigen::Vector3d(2, 30, -2));
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_THROW(median({}), FrameError);
}

TEST(FrameMaths, FusionRules) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Isometry3d a = pose({1.000, 0, 2}, aboutAxis(0.10, z));
  const Eigen::Isometry3d b = pose({1.004, 0, 2}, aboutAxis(0.14, z));
  FusionLimits limits;
  limits.max_position_difference = 0.01;
  limits.max_angle_difference = 0.1;

  FusionResult both = fusePoses(a, b, limits);
  ASSERT_TRUE(both.valid);
  EXPECT_EQ(both.source, FusionResult::Source::Both);
  EXPECT_NEAR((both.pose.translation() - Eigen::Vector3d(1.002, 0, 2)).norm(), 0, 1e-12);
  EXPECT_NEAR(rotationAngle(Eigen::Quaterniond(both.pose.rotation()), aboutAxis(0.12, z)), 0, 1e-9);
  EXPECT_NEAR(both.position_difference, 0.004, 1e-12);
  EXPECT_NEAR(both.angle_difference, 0.04, 1e-9);

  FusionResult only_second = fusePoses(std::nullopt, b, limits);
  ASSERT_TRUE(only_second.valid);
  EXPECT_EQ(only_second.source, FusionResult::Source::Second);
  EXPECT_TRUE(only_second.pose.isApprox(b));

  FusionResult far = fusePoses(a, pose({1.02, 0, 2}, aboutAxis(0.10, z)), limits);
  EXPECT_FALSE(far.valid);
  EXPECT_NE(far.reason.find("positions 0.02 m apart"), std::string::npos) << far.reason;

  FusionResult turned = fusePoses(a, pose({1, 0, 2}, aboutAxis(0.25, z)), limits);
  EXPECT_FALSE(turned.valid);
  EXPECT_NE(turned.reason.find("rotations"), std::string::npos) << turned.reason;

  FusionResult none = fusePoses(std::nullopt, std::nullopt, limits);
  EXPECT_FALSE(none.valid);
  EXPECT_EQ(none.source, FusionResult::Source::None);
}
