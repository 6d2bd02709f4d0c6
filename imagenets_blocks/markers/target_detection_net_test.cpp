// TargetDetectionNet runs the detection net of the target file's kind: the square marker's
// threshold search or the printed targets' net, with the same ports; nothing found is `failure`.
#include <gtest/gtest.h>

#include <geometry_msgs/PoseStamped.h>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <std_msgs/String.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"

using namespace imagenets;

namespace {

const std::string kTargets = "$(find imagenets_vision)/config/targets/";

std::string net(const std::string& target_net = "$(find imagenets_blocks)/config/nets/calibration_target_detection.yaml") {
  return R"(
blocks:
  camera: {type: imagenets/CameraInfoFile, properties: {path: $(find imagenets_vision)/config/cameras/stereo_left.yaml}}
  render: {type: imagenets/MarkerRenderer, properties: {target: )" + kTargets + R"(apriltag_36h11_60mm.yaml, pan: 40, tilt: 30, supersampling: 2}}
  detect:
    type: imagenets/TargetDetectionNet
    properties: {target: )" + kTargets + R"(apriltag_36h11_60mm.yaml, threads: 1,
                 marker_net: $(find imagenets_blocks)/config/nets/calibration_marker_detection.yaml,
                 target_net: )" + target_net + R"(}
links:
  - camera.camera_info -> render.camera_info
  - render.image -> detect.image
  - render.camera_info -> detect.camera_info
  - render.ground_truth -> detect.predicted_pose
)";
}

double errorMm(Executor& exec) {
  const auto det = exec.output<imagenets::MarkerDetection>("detect.detection");
  const auto truth = exec.output<geometry_msgs::PoseStamped>("render.ground_truth");
  return 1000 * (marker::fromPoseMsg(det->pose).translation() - marker::fromPoseMsg(truth->pose).translation()).norm();
}

}  // namespace

TEST(TargetDetectionNet, RunsTheDetectionNetOfTheTargetFilesKind) {
  Executor exec(Net::build(parseNetText(net(), "test", ".")), ExecutorOptions{1});
  // An AprilTag: the printed targets' net (no threshold search: no feedback trace).
  RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  auto det = exec.output<imagenets::MarkerDetection>("detect.detection");
  ASSERT_TRUE(det && det->found);
  EXPECT_EQ(det->point_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_LT(errorMm(exec), 1.0);
  EXPECT_FALSE(exec.output<FeedbackTrace>("detect.feedback_trace"));
  EXPECT_FALSE(exec.output<std_msgs::String>("detect.failure"));

  // The square marker: its threshold search, 8 points.
  exec.setPropertyText("render", "target", kTargets + "gripper_square_marker.yaml");
  exec.setPropertyText("detect", "target", kTargets + "gripper_square_marker.yaml");
  report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  det = exec.output<imagenets::MarkerDetection>("detect.detection");
  ASSERT_TRUE(det && det->found);
  EXPECT_EQ(det->points.size(), 8u);
  EXPECT_EQ(det->point_ids.size(), 8u);
  EXPECT_LT(errorMm(exec), 1.0);
  EXPECT_TRUE(exec.output<FeedbackTrace>("detect.feedback_trace"));

  // A ChArUco board that is not in the image: not found is a result (`failure`), not an error.
  exec.setPropertyText("detect", "target", kTargets + "charuco_5x7_5x5_100.yaml");
  report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  const auto failure = exec.output<std_msgs::String>("detect.failure");
  ASSERT_TRUE(failure);
  EXPECT_NE(failure->data.find("no valid candidate"), std::string::npos) << failure->data;
}

TEST(TargetDetectionNet, ATargetNetWithoutTheMarkerNetsInputsIsALoadError) {
  try {
    Net::build(parseNetText(net("$(find imagenets_blocks)/config/nets/threshold_demo.yaml"), "test", "."));
    FAIL() << "loaded";
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("property 'target_net'"), std::string::npos) << m;
    EXPECT_NE(m.find("has no input 'image'"), std::string::npos) << m;
  }
}
