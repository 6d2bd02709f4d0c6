// The simulator's view rendering: the per-pose world cache gives the same image as a full render,
// also when the world hides the marker, and bad scene files are reported clearly.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <camera_calibration_parsers/parse.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "friend_hw_sim/cameras.h"
#include "robot_description/robot_model.h"
#include "imagenets/vision/marker.h"
#include "imagenets/package_file.h"

using namespace friend_hw_sim;
using namespace robot_description;
namespace render = imagenets::render;

namespace {

struct SimScene {
  RobotModel model{loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"))};
  WorldScene world = loadWorldScene(imagenets::packageFile("friend_hw_sim", "config/scene.yaml"));
  render::Plane marker = imagenets::marker::markerPlane(
      imagenets::marker::MarkerDescription::load(imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml")), Eigen::Isometry3d::Identity());
  std::unique_ptr<render::Renderer> renderer;
  SimScene() {
    sensor_msgs::CameraInfo info;
    std::string name;
    EXPECT_TRUE(camera_calibration_parsers::readCalibration(imagenets::packageFile("friend_description", "config/cameras/friend_stereo_left.yaml"), name, info));
    renderer = std::make_unique<render::Renderer>(render::CameraModel::fromCameraInfo(info), 1);
  }
};

double maxDifference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  double mx = 0;
  cv::minMaxLoc(diff, nullptr, &mx);
  return mx;
}

}  // namespace

TEST(SimCameras, CachedWorldGivesTheSameImageAsAFullRender) {
  SimScene s;
  const auto& d = s.model.description();
  const Eigen::Isometry3d cam = s.model.leftCamera(d.head_calibration_pose);
  render::RenderOptions o;
  o.noise_sigma = 0;  // compare without noise; blur on
  WorldViewCache cache;
  for (const auto& arm : {d.arm_calibration_pose, d.arm_home}) {
    const Eigen::Isometry3d m = s.model.marker(arm);
    const cv::Mat full = renderView(*s.renderer, s.world, s.marker, m, cam, o, nullptr);
    const cv::Mat cached = renderView(*s.renderer, s.world, s.marker, m, cam, o, &cache);
    EXPECT_TRUE(cache.valid);
    // The cache stores the world at 8 bits: at most a gray level of rounding, twice.
    EXPECT_LE(maxDifference(full, cached), 2.0);
  }
  // The marker actually shows: the calibration-pose image differs from the world alone.
  const cv::Mat with_marker = renderView(*s.renderer, s.world, s.marker, s.model.marker(d.arm_calibration_pose), cam, o, &cache);
  EXPECT_GT(maxDifference(with_marker, cache.image), 100.0);
}

TEST(SimCameras, MarkerHiddenBehindABoxIsRenderedCorrectly) {
  SimScene s;
  const auto& d = s.model.description();
  const Eigen::Isometry3d cam = s.model.leftCamera(d.head_calibration_pose);
  // Put the marker behind the first box as seen from the camera: on the line camera -> box centre,
  // 20 cm further, facing the camera.
  Eigen::Vector3d box_centre = Eigen::Vector3d::Zero();
  for (const auto& p : s.world.planes) {
    if (p.name.rfind("box_1/", 0) == 0) box_centre += p.pose.translation() / 5.0;
  }
  const Eigen::Vector3d ray = (box_centre - cam.translation()).normalized();
  Eigen::Isometry3d m = cam;  // marker facing the camera: marker z = -camera z
  m.linear() = cam.linear() * Eigen::Vector3d(1, -1, -1).asDiagonal();
  m.translation() = box_centre + 0.2 * ray;
  render::RenderOptions o;
  o.noise_sigma = 0;
  WorldViewCache cache;
  const cv::Mat full = renderView(*s.renderer, s.world, s.marker, m, cam, o, nullptr);
  const cv::Mat cached = renderView(*s.renderer, s.world, s.marker, m, cam, o, &cache);
  EXPECT_LE(maxDifference(full, cached), 2.0);
  // The case is real: the marker centre is in view, and the world there is nearer than the marker.
  const Eigen::Vector3d c = cam.inverse() * m.translation();
  const cv::Point2d px = s.renderer->camera().project(c);
  ASSERT_TRUE(px.x > 0 && px.y > 0 && px.x < 1024 && px.y < 768) << px;
  EXPECT_LT(cache.depth.at<float>(static_cast<int>(px.y), static_cast<int>(px.x)), c.z() - 0.1);
}

TEST(SimCameras, BadSceneFileNamesFileAndKey) {
  // Unique per process: a fixed name in a shared /tmp may belong to another user's run.
  const std::string path =
      (std::filesystem::temp_directory_path() / ("friend_scene_bad_" + std::to_string(::getpid()) + ".yaml")).string();
  {
    std::ofstream file(path);
    file << "planes:\n  - {name: t, xyz: [0, 0], size: [1, 1]}\n";
    ASSERT_TRUE(file.good()) << "cannot write " << path;
  }
  try {
    loadWorldScene(path);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("planes[0].xyz"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
  EXPECT_THROW(loadWorldScene("/nonexistent/scene.yaml"), std::runtime_error);
}
