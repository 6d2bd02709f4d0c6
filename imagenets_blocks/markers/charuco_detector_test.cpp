// CharucoDetector in a net: a rendered ChArUco board (MarkerRenderer with a target file).
#include <gtest/gtest.h>

#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"

using namespace imagenets;

TEST(CharucoDetector, FindsTheChessboardCornersOfARenderedBoard) {
  const std::string yaml = R"(
blocks:
  camera: {type: imagenets/CameraInfoFile, properties: {path: $(find imagenets_vision)/config/cameras/stereo_left.yaml}}
  render: {type: imagenets/MarkerRenderer, properties: {target: $(find imagenets_vision)/config/targets/charuco_5x7_5x5_100.yaml,
                                                        distance: 0.55, pan: 100, tilt: 35, supersampling: 2}}
  board: {type: imagenets/CharucoDetector, properties: {target: $(find imagenets_vision)/config/targets/charuco_5x7_5x5_100.yaml}}
links:
  - camera.camera_info -> render.camera_info
  - render.image -> board.gray
  - render.camera_info -> board.camera_info
)";
  Executor exec(Net::build(parseNetText(yaml, "test", ".")), ExecutorOptions{1});
  const RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  const auto det = exec.output<imagenets::MarkerDetection>("board.detection");
  ASSERT_TRUE(det && det->found);
  EXPECT_EQ(det->point_ids.size(), 24u);
  const auto truth = exec.output<geometry_msgs::PoseStamped>("render.ground_truth");
  const Eigen::Isometry3d T = marker::fromPoseMsg(truth->pose), found = marker::fromPoseMsg(det->pose);
  EXPECT_LT((found.translation() - T.translation()).norm(), 0.001);
  EXPECT_LT(marker::rotationAngle(found, T), 0.2 * M_PI / 180);

  // The square marker is not this block's: refused when set (the block is configured with it),
  // saying where to look instead; the block keeps its board.
  try {
    exec.setPropertyText("board", "target", "$(find imagenets_vision)/config/targets/gripper_square_marker.yaml");
    FAIL() << "a square marker accepted";
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find("test: block 'board': property 'target': "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is a square_marker target; this block detects charuco"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(exec.run().ok());
  EXPECT_TRUE(exec.output<imagenets::MarkerDetection>("board.detection")->found);
}
