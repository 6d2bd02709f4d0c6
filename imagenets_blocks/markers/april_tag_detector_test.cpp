// The AprilTag block in a net: rendered tag (MarkerRenderer) -> AprilTagDetector.
#include <gtest/gtest.h>

#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>
#include <std_msgs/Float64.h>

#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"

using namespace imagenets;

TEST(AprilTagDetectorBlock, FindsTheRenderedTagInANet) {
  const std::string yaml = R"(
blocks:
  camera: {type: imagenets/CameraInfoFile, properties: {path: $(find imagenets_vision)/config/cameras/stereo_left.yaml}}
  render: {type: imagenets/MarkerRenderer, properties: {marker: "", apriltag_id: 7, pan: 120, tilt: 40, supersampling: 2}}
  tag: {type: imagenets/AprilTagDetector, properties: {id: 7, size: 0.06}}
links:
  - camera.camera_info -> render.camera_info
  - render.image -> tag.gray
  - render.camera_info -> tag.camera_info
)";
  Executor exec(Net::build(parseNetText(yaml, "test", ".")), ExecutorOptions{1});
  const RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  const auto det = exec.output<imagenets::MarkerDetection>("tag.detection");
  ASSERT_TRUE(det);
  EXPECT_TRUE(det->found);
  EXPECT_EQ(det->points.size(), 4u);
  const auto truth = exec.output<geometry_msgs::PoseStamped>("render.ground_truth");
  const Eigen::Isometry3d a = marker::fromPoseMsg(det->pose), b = marker::fromPoseMsg(truth->pose);
  EXPECT_LT((a.translation() - b.translation()).norm(), 0.003);
  EXPECT_LT(marker::rotationAngle(a, b), 2.0 * M_PI / 180);
  ASSERT_TRUE(exec.output<std_msgs::Float64>("tag.confidence"));

  exec.setProperty("tag", "id", 8);  // not in the image: detection without pose or confidence
  ASSERT_TRUE(exec.run().ok());
  EXPECT_FALSE(exec.output<imagenets::MarkerDetection>("tag.detection")->found);
  EXPECT_FALSE(exec.output<std_msgs::Float64>("tag.confidence"));
}
