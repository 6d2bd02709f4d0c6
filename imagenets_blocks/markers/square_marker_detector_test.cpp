// The detector block in nets: the shipped robust marker detection net (paper Fig. 3.3) and bad inputs.
#include <gtest/gtest.h>

#include <cmath>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/vision/render.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"

using namespace imagenets;

namespace {

std::unique_ptr<Executor> detectorOnly() {
  const std::string yaml = R"(
blocks:
  detector:
    type: imagenets/SquareMarkerDetector
    properties: {marker: $(find imagenets_vision)/config/markers/gripper.yaml}
)";
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "test", ".")), ExecutorOptions{1});
}

sensor_msgs::CameraInfoPtr friendInfo() {
  auto info = boost::make_shared<sensor_msgs::CameraInfo>();
  info->width = 1024;
  info->height = 768;
  info->K = {1400, 0, 515.2, 0, 1400, 381.6, 0, 0, 1};
  info->distortion_model = "plumb_bob";
  info->D = {-0.082, 0.124, 0.00042, -0.00031, 0.0};
  return info;
}

sensor_msgs::ImageConstPtr image(const cv::Mat& m, const std::string& enc) {
  return cv_bridge::CvImage(std_msgs::Header(), enc, m).toImageMsg();
}

std::string failures(const RunReport& r) {
  std::string s;
  for (const auto& f : r.failed) s += f + "\n";
  for (const auto& f : r.not_run) s += f + "\n";
  return s;
}

}  // namespace

TEST(RobustMarkerDetectionNet, FindsTheSampleMarkerWithFeedback) {
  // config/images/marker_sample.png: config/nets/marker_image_generation.yaml (pan 270, tilt 30, 600 mm).
  auto exec = Executor::loadFile("config/nets/robust_marker_detection.yaml", ExecutorOptions{2});
  const RunReport report = exec->run();
  ASSERT_TRUE(report.ok()) << failures(report);
  const auto det = exec->output<imagenets::MarkerDetection>("detector.detection");
  ASSERT_TRUE(det);
  EXPECT_TRUE(det->found);
  EXPECT_GT(det->confidence, 0.9);
  EXPECT_EQ(det->points.size(), 8u);
  const Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, 270 * M_PI / 180, 30 * M_PI / 180);
  const Eigen::Isometry3d pose = marker::fromPoseMsg(det->pose);
  EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.001);
  EXPECT_LT(marker::rotationAngle(pose, truth), 0.5 * M_PI / 180);
  const auto trace = exec->output<imagenets::FeedbackTrace>("threshold.feedback_trace");
  ASSERT_TRUE(trace);
  EXPECT_TRUE(trace->found);
  // The search starts at the image's Otsu threshold; on this clean image that one is good enough.
  const auto otsu = exec->output<std_msgs::Float64>("otsu.threshold");
  ASSERT_TRUE(otsu);
  ASSERT_FALSE(trace->values.empty());
  EXPECT_EQ(trace->values.front(), std::round(otsu->data));
  EXPECT_EQ(trace->stop_reason, "good_enough");
  EXPECT_EQ(trace->chosen_value, trace->values.front());
  EXPECT_GE(trace->chosen_score, 0.9);
  ASSERT_TRUE(exec->output<std_msgs::Float64>("detector.confidence"));
}

TEST(SquareMarkerDetectorBlock, BadInputsGiveNamedErrors) {
  const cv::Mat gray(768, 1024, CV_8UC1, cv::Scalar(128));
  {
    auto exec = detectorOnly();
    exec->setInput("detector.image", image(cv::Mat(), "mono8"));
    exec->setInput("detector.gray", image(gray, "mono8"));
    exec->setInput("detector.camera_info", sensor_msgs::CameraInfoConstPtr(friendInfo()));
    const RunReport r = exec->run();
    ASSERT_EQ(r.failed.size(), 1u);
    EXPECT_NE(r.failed[0].find("'image'"), std::string::npos) << r.failed[0];
  }
  {
    auto exec = detectorOnly();
    exec->setInput("detector.image", image(gray, "mono8"));
    exec->setInput("detector.gray", image(cv::Mat(768, 1024, CV_8UC3), "bgr8"));
    exec->setInput("detector.camera_info", sensor_msgs::CameraInfoConstPtr(friendInfo()));
    const RunReport r = exec->run();
    ASSERT_EQ(r.failed.size(), 1u);
    EXPECT_NE(r.failed[0].find("'gray'"), std::string::npos) << r.failed[0];
    EXPECT_NE(r.failed[0].find("bgr8"), std::string::npos) << r.failed[0];
  }
  {
    auto exec = detectorOnly();  // no camera_info: the block does not run, and says why
    exec->setInput("detector.image", image(gray, "mono8"));
    exec->setInput("detector.gray", image(gray, "mono8"));
    const RunReport r = exec->run();
    ASSERT_EQ(r.not_run.size(), 1u);
    EXPECT_NE(r.not_run[0].find("camera_info"), std::string::npos) << r.not_run[0];
  }
  {
    auto exec = detectorOnly();  // camera of another size
    auto info = friendInfo();
    info->width = 640;
    exec->setInput("detector.image", image(gray, "mono8"));
    exec->setInput("detector.gray", image(gray, "mono8"));
    exec->setInput("detector.camera_info", sensor_msgs::CameraInfoConstPtr(info));
    const RunReport r = exec->run();
    ASSERT_EQ(r.failed.size(), 1u);
    EXPECT_NE(r.failed[0].find("camera_info is 640x768"), std::string::npos) << r.failed[0];
  }
  {
    auto exec = detectorOnly();  // nothing to find: a detection with found = false, no confidence
    exec->setInput("detector.image", image(gray, "mono8"));
    exec->setInput("detector.gray", image(gray, "mono8"));
    exec->setInput("detector.camera_info", sensor_msgs::CameraInfoConstPtr(friendInfo()));
    const RunReport r = exec->run();
    ASSERT_TRUE(r.ok()) << failures(r);
    ASSERT_TRUE(exec->output<imagenets::MarkerDetection>("detector.detection"));
    EXPECT_FALSE(exec->output<imagenets::MarkerDetection>("detector.detection")->found);
    EXPECT_FALSE(exec->output<std_msgs::Float64>("detector.confidence"));
  }
}

TEST(SquareMarkerDetectorBlock, ABadBlurOfTheBlurredMatchIsALoadErrorNamingIt) {
  const std::string yaml = R"(
blocks:
  detector:
    type: imagenets/SquareMarkerDetector
    properties: {marker: $(find imagenets_vision)/config/markers/gripper.yaml, match_blur_px: [1, -2]}
)";
  try {
    Net::build(parseNetText(yaml, "test.yaml", "."));
    FAIL() << "no error";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("detector"), std::string::npos) << what;
    EXPECT_NE(what.find("match_blur_px"), std::string::npos) << what;
    EXPECT_NE(what.find("-2"), std::string::npos) << what;
  }
}

namespace {
struct Detected {
  imagenets::MarkerDetectionConstPtr detection;
  double reprojection_error = -1;
};

Detected detectIn(const cv::Mat& gray, const sensor_msgs::CameraInfoPtr& info, int refine_passes,
                  const geometry_msgs::PoseStamped* hint = nullptr) {
  auto exec = detectorOnly();
  exec->setProperty("detector", "refine_passes", refine_passes);
  cv::Mat binary;
  cv::threshold(gray, binary, 60, 255, cv::THRESH_BINARY);
  exec->setInput("detector.image", image(binary, "mono8"));
  exec->setInput("detector.gray", image(gray, "mono8"));
  exec->setInput("detector.camera_info", sensor_msgs::CameraInfoConstPtr(info));
  if (hint) exec->setInput("detector.pose_hint", boost::make_shared<const geometry_msgs::PoseStamped>(*hint));
  const RunReport r = exec->run();
  EXPECT_TRUE(r.ok()) << failures(r);
  Detected d;
  d.detection = exec->output<imagenets::MarkerDetection>("detector.detection");
  if (auto e = exec->output<std_msgs::Float64>("detector.reprojection_error")) d.reprojection_error = e->data;
  return d;
}
}  // namespace

TEST(SquareMarkerDetectorBlock, RegionOfInterestRefinementPassesAndReprojectionError) {
  const cv::Mat gray = cv::imread("config/images/marker_sample.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(gray.empty());
  const Detected full = detectIn(gray, friendInfo(), 2);
  ASSERT_TRUE(full.detection && full.detection->found);
  EXPECT_EQ(full.reprojection_error, full.detection->reprojection_error);

  // The same marker in a region of the image (camera_info roi as ROS defines it): full-image points.
  cv::Rect box = cv::boundingRect(std::vector<cv::Point2f>{
      cv::Point2f(full.detection->points[0].x, full.detection->points[0].y),
      cv::Point2f(full.detection->points[2].x, full.detection->points[2].y)});
  box = cv::Rect(box.x - 60, box.y - 60, box.width + 120, box.height + 120) & cv::Rect(0, 0, gray.cols, gray.rows);
  auto region = friendInfo();
  region->roi.x_offset = box.x;
  region->roi.y_offset = box.y;
  region->roi.width = box.width;
  region->roi.height = box.height;
  const Detected cropped = detectIn(gray(box).clone(), region, 2);
  ASSERT_TRUE(cropped.detection && cropped.detection->found);
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_NEAR(cropped.detection->points[i].x, full.detection->points[i].x, 0.01) << i;
    EXPECT_NEAR(cropped.detection->points[i].y, full.detection->points[i].y, 0.01) << i;
  }
  EXPECT_NEAR(cropped.detection->pose.position.z, full.detection->pose.position.z, 1e-5);

  // Pixel corners only (no sub-pixel refinement): found, but the corners fit worse.
  const Detected coarse = detectIn(gray, friendInfo(), 0);
  ASSERT_TRUE(coarse.detection && coarse.detection->found);
  EXPECT_GT(coarse.reprojection_error, full.reprojection_error);
  EXPECT_NEAR(coarse.detection->points[0].x, full.detection->points[0].x, 2.0);

  // A pose hint is accepted (it only decides between two equally fitting planar poses).
  geometry_msgs::PoseStamped hint;
  hint.pose = full.detection->pose;
  const Detected hinted = detectIn(gray, friendInfo(), 2, &hint);
  ASSERT_TRUE(hinted.detection && hinted.detection->found);
  EXPECT_NEAR(hinted.detection->pose.position.x, full.detection->pose.position.x, 1e-9);

  // A roi outside the image is named.
  region->roi.x_offset = 1000;
  auto exec = detectorOnly();
  exec->setInput("detector.image", image(gray(box).clone(), "mono8"));
  exec->setInput("detector.gray", image(gray(box).clone(), "mono8"));
  exec->setInput("detector.camera_info", sensor_msgs::CameraInfoConstPtr(region));
  const RunReport r = exec->run();
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_NE(r.failed[0].find("input 'camera_info': roi"), std::string::npos) << r.failed[0];
  EXPECT_NE(r.failed[0].find("is not inside the 1024x768 image"), std::string::npos) << r.failed[0];
}
