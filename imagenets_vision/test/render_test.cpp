#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/vision/render.h"

using namespace imagenets::render;

namespace {

CameraModel testCamera(bool distorted) {
  CameraModel cam;
  cam.width = 320;
  cam.height = 240;
  cam.K = cv::Matx33d(400, 0, 161.3, 0, 400, 118.7, 0, 0, 1);
  if (distorted) cam.D = {-0.2, 0.1, 0.001, -0.002, 0.0};
  return cam;
}

Plane whitePatch(double size, const Eigen::Vector3d& centre) {
  Plane p;
  p.texture = cv::Mat(8, 8, CV_8UC1, cv::Scalar(255));
  p.width = p.height = size;
  p.pose = Eigen::Isometry3d::Identity();
  p.pose.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  p.pose.translation() = centre;
  return p;
}

RenderOptions clean() {
  RenderOptions o;
  o.background = 0.0;
  o.blur_sigma = 0.0;
  o.noise_sigma = 0.0;
  return o;
}

Scene sceneOf(const Plane& p) {
  Scene s;
  s.planes.push_back(p);
  s.light.ambient = 1.0;
  s.light.diffuse = 0.0;
  return s;
}

}  // namespace

TEST(Renderer, HeadOnPatchCoversItsProjectedArea) {
  Renderer r(testCamera(false), 4);
  cv::Mat img = r.render(sceneOf(whitePatch(0.1, {0, 0, 1.0})), clean());
  ASSERT_EQ(img.type(), CV_8UC1);
  const double area = cv::sum(img)[0] / 255.0;
  EXPECT_NEAR(area, 40.0 * 40.0, 40.0);  // 0.1 m at 1 m with f = 400 px: 40 x 40 px
}

TEST(Renderer, SmallPatchLandsWhereTheDistortedCameraProjectsIt) {
  const CameraModel cam = testCamera(true);
  Renderer r(cam, 4);
  const Eigen::Vector3d centre(0.25, -0.18, 1.0);  // far off-centre: distortion matters here
  cv::Mat img = r.render(sceneOf(whitePatch(0.01, centre)), clean());
  const cv::Moments m = cv::moments(img);
  const cv::Point2d expected = cam.project(centre);
  EXPECT_NEAR(m.m10 / m.m00, expected.x, 0.05);
  EXPECT_NEAR(m.m01 / m.m00, expected.y, 0.05);
}

TEST(Renderer, BackFacesAreCulledUnlessTwoSided) {
  Renderer r(testCamera(false), 2);
  Plane p = whitePatch(0.1, {0, 0, 1.0});
  p.pose.linear() = Eigen::Matrix3d::Identity();  // normal points away from the camera
  EXPECT_EQ(cv::countNonZero(r.render(sceneOf(p), clean())), 0);
  p.two_sided = true;
  EXPECT_GT(cv::countNonZero(r.render(sceneOf(p), clean())), 1000);
}

TEST(Renderer, NearerPlaneHidesFartherOneAndDepthIsReported) {
  Renderer r(testCamera(false), 1);
  Scene s = sceneOf(whitePatch(0.2, {0, 0, 2.0}));
  Plane dark = whitePatch(0.05, {0, 0, 1.0});
  dark.albedo = 0.2;
  s.planes.push_back(dark);
  cv::Mat img = r.render(s, clean());
  EXPECT_NEAR(img.at<uchar>(119, 161), 51, 1);   // the near, dark patch
  EXPECT_NEAR(img.at<uchar>(119, 161 + 15), 255, 1);  // the far, white one around it
  cv::Mat depth = r.renderDepth(s);
  EXPECT_NEAR(depth.at<float>(119, 161), 1.0, 1e-4);
  EXPECT_NEAR(depth.at<float>(119, 161 + 15), 2.0, 1e-4);
  EXPECT_EQ(depth.at<float>(5, 5), 0.0f);
}

TEST(Renderer, LambertShadingIlluminationAndSeededNoise) {
  Renderer r(testCamera(false), 1);
  Scene s = sceneOf(whitePatch(0.2, {0, 0, 1.0}));
  s.light.ambient = 0.2;
  s.light.diffuse = 0.8;
  s.light.direction = Eigen::Vector3d(0, 0, 1);  // straight onto the patch
  RenderOptions o = clean();
  o.illumination = 0.5;
  EXPECT_NEAR(r.render(s, o).at<uchar>(120, 160), 128, 1);
  s.light.direction = Eigen::Vector3d(1, 0, 1);  // 45 degrees: cos = 0.707
  EXPECT_NEAR(r.render(s, o).at<uchar>(120, 160), std::lround(127.5 * (0.2 + 0.8 * std::sqrt(0.5))), 1);
  o.noise_sigma = 3.0;
  o.seed = 7;
  cv::Mat a = r.render(s, o), b = r.render(s, o);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  o.seed = 8;
  EXPECT_GT(cv::norm(a, r.render(s, o), cv::NORM_INF), 0.0);
}

TEST(Renderer, CameraInfoConversionRejectsBadModels) {
  sensor_msgs::CameraInfo info;
  EXPECT_THROW(CameraModel::fromCameraInfo(info), std::invalid_argument);
  info.width = 640;
  info.height = 480;
  info.K = {500, 0, 320, 0, 500, 240, 0, 0, 1};
  info.distortion_model = "equidistant";
  info.D = {0.1, 0, 0, 0};
  EXPECT_THROW(CameraModel::fromCameraInfo(info), std::invalid_argument);
  info.distortion_model = "plumb_bob";
  info.D = {0.1, 0, 0, 0, 0};
  const CameraModel cam = CameraModel::fromCameraInfo(info);
  EXPECT_EQ(cam.D.size(), 5u);
  EXPECT_EQ(cam.width, 640);
}

TEST(Renderer, LookAtOriginPoseKeepsTheDistanceAndTilt) {
  const Eigen::Isometry3d T = lookAtOriginPose(0.6, 0.3, 0.5);
  EXPECT_NEAR(T.translation().norm(), 0.6, 1e-12);
  EXPECT_NEAR(T.translation().x(), 0.0, 1e-12);  // the origin is on the optical axis
  EXPECT_NEAR(T.translation().y(), 0.0, 1e-12);
  // Angle between the plane normal and the viewing direction is the tilt.
  EXPECT_NEAR(std::acos(-T.linear().col(2).z()), 0.5, 1e-12);
}
