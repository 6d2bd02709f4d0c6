// TargetDetector takes AprilTag and ChArUco target files alike; in a region of the image (a
// camera_info with a roi, as CropAroundPose gives) it reports full-image pixels.
#include <gtest/gtest.h>

#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"

using namespace imagenets;

TEST(TargetDetector, TakesEitherKindOfTargetAndReportsFullImagePixelsInARegion) {
  const std::string yaml = R"(
blocks:
  camera: {type: imagenets/CameraInfoFile, properties: {path: $(find imagenets_vision)/config/cameras/stereo_left.yaml}}
  render: {type: imagenets/MarkerRenderer, properties: {target: $(find imagenets_vision)/config/targets/apriltag_36h11_60mm.yaml,
                                                        distance: 0.6, pan: 300, tilt: 30, supersampling: 2}}
  whole: {type: imagenets/TargetDetector, properties: {target: $(find imagenets_vision)/config/targets/apriltag_36h11_60mm.yaml}}
  region: {type: imagenets/CropAroundPose, properties: {size: 0.06, margin_px: 40}}
  part: {type: imagenets/TargetDetector, properties: {target: $(find imagenets_vision)/config/targets/apriltag_36h11_60mm.yaml}}
links:
  - camera.camera_info -> render.camera_info
  - render.image -> whole.gray
  - render.camera_info -> whole.camera_info
  - render.image -> region.image
  - render.camera_info -> region.camera_info
  - render.ground_truth -> region.pose
  - region.image -> part.gray
  - region.camera_info -> part.camera_info
)";
  Executor exec(Net::build(parseNetText(yaml, "test", ".")), ExecutorOptions{1});
  RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  const auto whole = exec.output<imagenets::MarkerDetection>("whole.detection");
  const auto part = exec.output<imagenets::MarkerDetection>("part.detection");
  ASSERT_TRUE(whole->found && part->found);
  ASSERT_EQ(whole->point_ids, (std::vector<int>{0, 1, 2, 3}));
  ASSERT_EQ(part->point_ids, whole->point_ids);
  for (size_t i = 0; i < whole->points.size(); ++i) {
    EXPECT_NEAR(part->points[i].x, whole->points[i].x, 0.05);
    EXPECT_NEAR(part->points[i].y, whole->points[i].y, 0.05);
  }

  // The same block on a ChArUco board.
  const std::string board = "$(find imagenets_vision)/config/targets/charuco_5x7_5x5_100.yaml";
  exec.setPropertyText("render", "target", board);
  exec.setPropertyText("whole", "target", board);
  report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  const auto b = exec.output<imagenets::MarkerDetection>("whole.detection");
  ASSERT_TRUE(b->found);
  EXPECT_GT(b->point_ids.size(), 20u);
  const auto truth = exec.output<geometry_msgs::PoseStamped>("render.ground_truth");
  EXPECT_LT((marker::fromPoseMsg(b->pose).translation() - marker::fromPoseMsg(truth->pose).translation()).norm(), 0.001);
}
