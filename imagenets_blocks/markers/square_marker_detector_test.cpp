// The detector block in nets: the shipped robust marker detection net (paper Fig. 3.3) and bad inputs.
#include <gtest/gtest.h>

#include <cv_bridge/cv_bridge.h>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <opencv2/imgcodecs.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/marker.h"
#include "imagenets/blocks/marker_msgs.h"
#include "imagenets/blocks/render.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"

using namespace imagenets;

namespace {

std::unique_ptr<Executor> detectorOnly() {
  const std::string yaml = R"(
blocks:
  detector:
    type: imagenets/SquareMarkerDetector
    properties: {marker: config/markers/gripper.yaml}
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
  EXPECT_EQ(trace->values.size(), 41u);  // 40..80
  EXPECT_GE(trace->chosen_value, 40);
  EXPECT_LE(trace->chosen_value, 80);
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
