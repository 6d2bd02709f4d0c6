// The square-marker detector on rendered images whose true pose is known.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "imagenets/vision/marker.h"

using namespace imagenets;
using marker::Detection;
using marker::MarkerDescription;

namespace {

const double kDeg = M_PI / 180.0;

render::CameraModel friendCamera() {
  render::CameraModel cam;
  cam.width = 1024;
  cam.height = 768;
  cam.K = cv::Matx33d(1400, 0, 515.2, 0, 1400, 381.6, 0, 0, 1);
  cam.D = {-0.082, 0.124, 0.00042, -0.00031, 0.0};
  return cam;
}

const MarkerDescription& gripper() {
  static const MarkerDescription m = MarkerDescription::load("config/markers/gripper.yaml");
  return m;
}

struct Shot {
  cv::Mat gray, binary;
};

Shot shoot(const render::Renderer& r, const MarkerDescription& m, const Eigen::Isometry3d& pose, int threshold = 60,
           double illumination = 1.0, double blur = 0.7) {
  render::Scene scene;
  scene.planes.push_back(marker::markerPlane(m, pose));
  scene.light.direction = Eigen::Vector3d(0.3, 0.4, 1.0);
  render::RenderOptions o;
  o.illumination = illumination;
  o.blur_sigma = blur;
  o.noise_sigma = 2.0;
  o.seed = 11;
  Shot s;
  s.gray = r.render(scene, o);
  cv::threshold(s.gray, s.binary, threshold, 255, cv::THRESH_BINARY);
  return s;
}

double positionErrorMm(const Detection& d, const Eigen::Isometry3d& truth) {
  return 1000.0 * (d.pose.translation() - truth.translation()).norm();
}

}  // namespace

TEST(MarkerDescription, LoadsTheGripperMarkerAndNamesBadFiles) {
  const MarkerDescription& m = gripper();
  EXPECT_EQ(m.name, "gripper");
  EXPECT_DOUBLE_EQ(m.size, 0.060);
  EXPECT_DOUBLE_EQ(m.border, 0.25);
  EXPECT_FALSE(m.pattern.empty());
  EXPECT_NEAR(m.innerSize(), 0.030, 1e-12);
  try {
    MarkerDescription::load("config/markers/no_such_marker.yaml");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_marker.yaml"), std::string::npos) << e.what();
  }
  const cv::Mat tex = m.texture(4000.0, true);  // 60 mm + 2 x 15 mm at 4 px/mm
  EXPECT_EQ(tex.cols, 360);
  EXPECT_EQ(tex.at<uchar>(5, 5), 255);      // margin
  EXPECT_EQ(tex.at<uchar>(70, 70), 0);      // border
}

TEST(MarkerDetector, FindsTheRenderedMarkerAtItsTruePose) {
  const render::Renderer r(friendCamera(), 4);
  for (const auto& pt : std::vector<std::pair<double, double>>{{0, 0}, {30, 20}, {270, 30}, {140, 60}, {200, 70}}) {
    const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, pt.first * kDeg, pt.second * kDeg);
    const Shot s = shoot(r, gripper(), truth);
    const Detection d = marker::detect(s.gray, s.binary, friendCamera(), gripper());
    ASSERT_TRUE(d.found) << "pan " << pt.first << " tilt " << pt.second;
    EXPECT_GT(d.confidence, 0.9);
    EXPECT_LT(positionErrorMm(d, truth), 2.0) << "pan " << pt.first << " tilt " << pt.second;
    EXPECT_LT(marker::rotationAngle(d.pose, truth) / kDeg, 1.0) << "pan " << pt.first << " tilt " << pt.second;
    // Both IPPE solutions are kept; the chosen one fits the 8 points at least as well.
    EXPECT_LE(d.reprojection_error, d.alt_reprojection_error + 1e-9);
    EXPECT_LT(d.reprojection_error, 0.3);
  }
}

TEST(MarkerDetector, CornersDoNotMoveWithTheThreshold) {
  const render::Renderer r(friendCamera(), 4);
  const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, 40 * kDeg, 45 * kDeg);
  const Shot lo = shoot(r, gripper(), truth, 40), hi = shoot(r, gripper(), truth, 120);
  const Detection a = marker::detect(lo.gray, lo.binary, friendCamera(), gripper());
  const Detection b = marker::detect(hi.gray, hi.binary, friendCamera(), gripper());
  ASSERT_TRUE(a.found && b.found);
  for (int i = 0; i < 8; ++i) EXPECT_LT(cv::norm(a.points[i] - b.points[i]), 0.05) << "point " << i;
}

TEST(MarkerDetector, ASmallInnerSquareIsLeftOutOfThePoseFit) {
  // 1.26 m away, seen at 70 deg, blur 1.2 px: the inner square is ~11 px high and lies among the
  // pattern's cells, its corners are off by up to a pixel and (counted twice) spoil the pose.
  const render::Renderer r(friendCamera(), 3);
  const Eigen::Isometry3d truth = render::lookAtOriginPose(1.256, 105 * kDeg, 70 * kDeg);
  const Shot s = shoot(r, gripper(), truth, 60, 1.0, 1.2);
  marker::DetectorOptions with_inner, outer_only;
  with_inner.refine_passes = outer_only.refine_passes = 4;
  outer_only.min_inner_side_px = 50;
  const Detection a = marker::detect(s.gray, s.binary, friendCamera(), gripper(), with_inner);
  const Detection b = marker::detect(s.gray, s.binary, friendCamera(), gripper(), outer_only);
  ASSERT_TRUE(a.found);
  ASSERT_TRUE(b.found);
  EXPECT_LT(positionErrorMm(b, truth), 1.0);
  EXPECT_LT(positionErrorMm(b, truth), 0.5 * positionErrorMm(a, truth));
  EXPECT_LT(b.reprojection_error, a.reprojection_error);  // over the fitted (outer) corners only
  // The inner corners are still reported.
  EXPECT_GT(cv::norm(b.points[4] - b.points[6]), 5.0);
  // Close and head-on the inner square is large: the same option keeps it in the fit.
  const Eigen::Isometry3d near = render::lookAtOriginPose(0.6, 0, 0);
  const Shot n = shoot(r, gripper(), near);
  const Detection c = marker::detect(n.gray, n.binary, friendCamera(), gripper(), outer_only);
  marker::DetectorOptions inner_always = outer_only;
  inner_always.min_inner_side_px = 0;
  const Detection e = marker::detect(n.gray, n.binary, friendCamera(), gripper(), inner_always);
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.pose.translation(), e.pose.translation());
}

TEST(MarkerDetector, PatternFixesTheOrientation) {
  const render::Renderer r(friendCamera(), 3);
  // The same view, the marker turned by quarter turns in its plane: the square border looks the
  // same, only the pattern tells them apart.
  for (int quarter = 0; quarter < 4; ++quarter) {
    const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, quarter * 90 * kDeg + 15 * kDeg, 25 * kDeg);
    const Shot s = shoot(r, gripper(), truth);
    const Detection d = marker::detect(s.gray, s.binary, friendCamera(), gripper());
    ASSERT_TRUE(d.found);
    EXPECT_LT(marker::rotationAngle(d.pose, truth) / kDeg, 1.0) << "quarter " << quarter;
  }
}

TEST(MarkerDetector, ConfidenceIsLowForAWrongPattern) {
  const render::Renderer r(friendCamera(), 3);
  MarkerDescription other = gripper();
  other.name = "other";
  other.pattern = cv::Mat(7, 7, CV_8UC1, cv::Scalar(255));
  other.pattern(cv::Rect(1, 1, 2, 5)).setTo(0);  // a different glyph: two bars
  other.pattern(cv::Rect(4, 2, 2, 2)).setTo(0);
  const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, 10 * kDeg, 20 * kDeg);
  const Shot s = shoot(r, other, truth);
  const Detection wrong = marker::detect(s.gray, s.binary, friendCamera(), gripper());
  EXPECT_FALSE(wrong.found);
  EXPECT_LT(wrong.confidence, 0.5);
  const Detection right = marker::detect(s.gray, s.binary, friendCamera(), other);
  EXPECT_TRUE(right.found);
  EXPECT_GT(right.confidence, 0.9);
}

TEST(MarkerDetector, AFarBlurredMarkerIsMatchedAgainstItsBlurredPattern) {
  // 1.39 m away at 60 deg, blur 1.9 px: the pattern's cells are 1..2 px and smeared into each
  // other, so the sharp pattern matches poorly. Matched against the pattern as the camera blurs
  // it, the same candidate is clearly the marker, in the right orientation.
  const render::Renderer r(friendCamera(), 3);
  for (const double pan : {20.0, 200.0}) {
    const Eigen::Isometry3d truth = render::lookAtOriginPose(1.39, pan * kDeg, 60 * kDeg);
    const Shot s = shoot(r, gripper(), truth, 60, 1.0, 1.9);
    marker::DetectorOptions sharp;
    sharp.refine_passes = 4;
    sharp.min_confidence = 0.7;  // as the nets that match blurred patterns set it
    marker::DetectorOptions blurred = sharp;
    blurred.match_blur_px = {1, 2};
    const Detection a = marker::detect(s.gray, s.binary, friendCamera(), gripper(), sharp);
    const Detection b = marker::detect(s.gray, s.binary, friendCamera(), gripper(), blurred);
    EXPECT_LT(a.confidence, 0.6) << "pan " << pan;
    ASSERT_TRUE(b.found) << "pan " << pan;
    EXPECT_GT(b.confidence, 0.85) << "pan " << pan;
    EXPECT_LT(marker::rotationAngle(b.pose, truth) / kDeg, 5.0) << "pan " << pan;
    EXPECT_LT(positionErrorMm(b, truth), 15.0) << "pan " << pan;  // 1 % of the distance
    // A wrong pattern stays below the limit under the same blurred match.
    MarkerDescription other = gripper();
    other.pattern = cv::Mat(6, 6, CV_8UC1, cv::Scalar(255));
    other.pattern(cv::Rect(1, 1, 1, 4)).setTo(0);  // a different glyph: two bars
    other.pattern(cv::Rect(3, 1, 1, 4)).setTo(0);
    const Shot o = shoot(r, other, truth, 60, 1.0, 1.9);
    const Detection wrong = marker::detect(o.gray, o.binary, friendCamera(), gripper(), blurred);
    EXPECT_FALSE(wrong.found) << "pan " << pan << ": confidence " << wrong.confidence;
    // Also where the sharp limit is lower (the calibration's is 0.6): a blurred match counts from
    // 0.7 on, so the wrong pattern's (which is above 0.5) does not pass.
    marker::DetectorOptions lenient = blurred;
    lenient.min_confidence = 0.5;
    const Detection still_wrong = marker::detect(o.gray, o.binary, friendCamera(), gripper(), lenient);
    EXPECT_FALSE(still_wrong.found) << "pan " << pan << ": confidence " << still_wrong.confidence;
  }
}

TEST(MarkerDetector, TheEdgeModelCanBeKeptToSmallMarkers) {
  // edge_model_max_side_px: near (sides ~140 px) the profile refinement's corners are kept, far
  // (sides ~60 px) the edge model's.
  const render::Renderer r(friendCamera(), 3);
  marker::DetectorOptions profile, edge, small_only;
  profile.refine_passes = edge.refine_passes = 4;
  edge.edge_model = true;
  small_only = edge;
  small_only.edge_model_max_side_px = 110;
  for (const double distance : {0.6, 1.3}) {
    const Eigen::Isometry3d truth = render::lookAtOriginPose(distance, 30 * kDeg, 20 * kDeg);
    const Shot s = shoot(r, gripper(), truth, 60, 0.4, 1.2);
    const Detection a = marker::detect(s.gray, s.binary, friendCamera(), gripper(), profile);
    const Detection b = marker::detect(s.gray, s.binary, friendCamera(), gripper(), edge);
    const Detection c = marker::detect(s.gray, s.binary, friendCamera(), gripper(), small_only);
    ASSERT_TRUE(a.found && b.found && c.found) << distance;
    EXPECT_GT(cv::norm(a.points[0] - b.points[0]), 1e-6) << distance;  // the two refinements differ
    const Detection& expected = distance < 1 ? a : b;
    for (int i = 0; i < 8; ++i) EXPECT_EQ(c.points[i], expected.points[i]) << "distance " << distance << " point " << i;
  }
}

TEST(MarkerDetector, LensDistortionIsTakenIntoAccount) {
  render::CameraModel cam = friendCamera();
  cam.D = {-0.35, 0.2, 0.0, 0.0, 0.0};  // strong barrel distortion
  const render::Renderer r(cam, 3);
  // Marker near the image corner, where distortion displaces it by many pixels.
  Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, 20 * kDeg, 15 * kDeg);
  truth.translation() += Eigen::Vector3d(0.17, 0.12, 0.0);
  const Shot s = shoot(r, gripper(), truth);
  const Detection d = marker::detect(s.gray, s.binary, cam, gripper());
  ASSERT_TRUE(d.found);
  EXPECT_LT(positionErrorMm(d, truth), 2.0);
  render::CameraModel ignorant = cam;
  ignorant.D.clear();
  const Detection bad = marker::detect(s.gray, s.binary, ignorant, gripper());
  ASSERT_TRUE(bad.found);
  EXPECT_GT(positionErrorMm(bad, truth), 10.0);  // shows the model is really used
}

TEST(MarkerDetector, PoseHintPicksAmongAmbiguousIppeSolutions) {
  const render::Renderer r(friendCamera(), 3);
  const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, 0, 5 * kDeg);  // nearly head-on: ambiguous
  const Shot s = shoot(r, gripper(), truth);
  const Detection free = marker::detect(s.gray, s.binary, friendCamera(), gripper());
  ASSERT_TRUE(free.found);
  EXPECT_GT(marker::rotationAngle(free.pose, free.alt_pose), 0.0);  // two distinct solutions
  marker::DetectorOptions options;
  options.ambiguity_ratio = 1e9;  // treat them as ambiguous: the hint decides
  options.pose_hint = &free.alt_pose;
  const Detection hinted = marker::detect(s.gray, s.binary, friendCamera(), gripper(), options);
  ASSERT_TRUE(hinted.found);
  EXPECT_LT(marker::rotationAngle(hinted.pose, free.alt_pose), 1e-9);
  EXPECT_LT(marker::rotationAngle(hinted.alt_pose, free.pose), 1e-9);
}

TEST(MarkerDetector, QuadrilateralsFarSmallerThanTheHintedMarkerAreNotExamined) {
  const render::Renderer r(friendCamera(), 3);
  const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, 30 * kDeg, 20 * kDeg);
  Shot s = shoot(r, gripper(), truth);
  // Dark squares 20-40 px wide elsewhere (the marker's sides are ~140 px): specks and small parts.
  for (int i = 0; i < 6; ++i) {
    const cv::Rect square(40 + 150 * i, 40 + 8 * i, 20 + 4 * i, 20 + 4 * i);
    s.gray(square).setTo(20);
    s.binary(square).setTo(0);
  }
  marker::DetectorOptions options;
  options.pose_hint = &truth;
  const Detection all = marker::detect(s.gray, s.binary, friendCamera(), gripper(), options);
  options.min_side_of_hint = 0.5;
  const Detection large = marker::detect(s.gray, s.binary, friendCamera(), gripper(), options);
  ASSERT_TRUE(all.found && large.found);
  EXPECT_GE(all.candidates, 7);  // the marker and the six squares at least
  EXPECT_EQ(large.candidates, 1) << all.candidates << " without the limit";
  for (int i = 0; i < 8; ++i) EXPECT_EQ(all.points[i], large.points[i]) << "point " << i;
}

TEST(MarkerDetector, RejectsBadInputs) {
  const cv::Mat gray(768, 1024, CV_8UC1, cv::Scalar(128));
  EXPECT_THROW(marker::detect(cv::Mat(), gray, friendCamera(), gripper()), std::invalid_argument);
  EXPECT_THROW(marker::detect(gray, cv::Mat(10, 10, CV_8UC1), friendCamera(), gripper()), std::invalid_argument);
  EXPECT_THROW(marker::detect(cv::Mat(480, 640, CV_8UC1), cv::Mat(480, 640, CV_8UC1), friendCamera(), gripper()),
               std::invalid_argument);
  const Detection none = marker::detect(gray, gray, friendCamera(), gripper());
  EXPECT_FALSE(none.found);
}
