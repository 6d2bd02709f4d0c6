// AprilTagTargetDetector in a net: a rendered grid of tags (MarkerRenderer with a target file).
#include <gtest/gtest.h>

#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>
#include <std_msgs/Float64.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/package_file.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/vision/target.h"

using namespace imagenets;

namespace {

std::string net(const std::string& target, const std::string& detector_target) {
  return R"(
blocks:
  camera: {type: imagenets/CameraInfoFile, properties: {path: $(find imagenets_vision)/config/cameras/stereo_left.yaml}}
  render: {type: imagenets/MarkerRenderer, properties: {target: )" + target + R"(, distance: 0.5, pan: 200, tilt: 25, supersampling: 2}}
  tags: {type: imagenets/AprilTagTargetDetector, properties: {target: )" + detector_target + R"(}}
links:
  - camera.camera_info -> render.camera_info
  - render.image -> tags.gray
  - render.camera_info -> tags.camera_info
)";
}

const std::string kGrid = "$(find imagenets_vision)/config/targets/aprilgrid_36h11_4x3.yaml";

}  // namespace

TEST(AprilTagTargetDetector, FindsEveryTagOfARenderedGridWithTheirIds) {
  Executor exec(Net::build(parseNetText(net(kGrid, kGrid), "test", ".")), ExecutorOptions{1});
  const RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  const auto det = exec.output<imagenets::MarkerDetection>("tags.detection");
  ASSERT_TRUE(det && det->found);
  ASSERT_EQ(det->points.size(), 48u);
  ASSERT_EQ(det->point_ids.size(), 48u);
  ASSERT_EQ(det->object_points.size(), 48u);
  EXPECT_EQ(det->marker, "aprilgrid_36h11_4x3");
  // Every point is where the true pose projects its id's corner.
  const auto truth = exec.output<geometry_msgs::PoseStamped>("render.ground_truth");
  const Eigen::Isometry3d T = marker::fromPoseMsg(truth->pose), found = marker::fromPoseMsg(det->pose);
  EXPECT_LT((found.translation() - T.translation()).norm(), 0.001);
  EXPECT_LT(marker::rotationAngle(found, T), 0.2 * M_PI / 180);
  const auto corners = target::TargetDescription::load(packageFile("imagenets_vision", "config/targets/aprilgrid_36h11_4x3.yaml")).corners();
  for (size_t i = 0; i < det->point_ids.size(); ++i) {
    const Eigen::Vector3d p = corners.at(det->point_ids[i]);
    EXPECT_NEAR(det->object_points[i].x, p.x(), 1e-12);
    EXPECT_NEAR(det->object_points[i].y, p.y(), 1e-12);
  }
  EXPECT_TRUE(exec.output<std_msgs::Float64>("tags.confidence"));
  EXPECT_LT(exec.output<std_msgs::Float64>("tags.reprojection_error")->data, 0.3);
}

TEST(AprilTagTargetDetector, AnotherKindOfTargetIsALoadErrorNamingTheFile) {
  try {
    Net::build(parseNetText(net(kGrid, "$(find imagenets_vision)/config/targets/charuco_5x7_5x5_100.yaml"), "test", "."));
    FAIL() << "a ChArUco target was taken";
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("tags"), std::string::npos) << m;
    EXPECT_NE(m.find("property 'target'"), std::string::npos) << m;
    EXPECT_NE(m.find("charuco_5x7_5x5_100.yaml is a charuco target; this block detects apriltag"), std::string::npos) << m;
  }
}
