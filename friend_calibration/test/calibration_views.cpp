#include "calibration_views.h"

#include <random>

#include <camera_calibration_parsers/parse.h>

#include "imagenets_calibration/calibration.h"
#include "friend_hw_sim/cameras.h"
#include "friend_hw_sim/true_robot.h"
#include "robot_description/robot_model.h"
#include "imagenets/package_file.h"

namespace imagenets_calibration {

namespace render = imagenets::render;

CalibrationViews renderCalibrationViews() {
  const std::string desc_path = imagenets::packageFile("friend_description", "config/robot.yaml");
  const auto nominal_desc = robot_description::loadRobotDescription(desc_path);
  const RobotModel nominal(nominal_desc);
  const RobotModel truth(friend_hw_sim::applyTrueError(
      nominal_desc, friend_hw_sim::loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), nominal_desc)));
  const auto world = friend_hw_sim::loadWorldScene(imagenets::packageFile("friend_hw_sim", "config/scene.yaml"));
  CalibrationViews out;
  out.marker = imagenets::marker::MarkerDescription::load(imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"));
  const auto& marker = out.marker;
  const render::Plane plane = imagenets::marker::markerPlane(marker, Eigen::Isometry3d::Identity());
  sensor_msgs::CameraInfo info[2];
  std::string name;
  camera_calibration_parsers::readCalibration(nominal_desc.left_camera_info, name, info[0]);
  camera_calibration_parsers::readCalibration(nominal_desc.right_camera_info, name, info[1]);
  const render::Renderer renderer[2] = {render::Renderer(render::CameraModel::fromCameraInfo(info[0]), 2),
                                        render::Renderer(render::CameraModel::fromCameraInfo(info[1]), 2)};

  // The joint method's ten poses, twice: clean, and with a reflection in every other view.
  std::vector<CalibrationView>& views = out.views;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const auto poses = calibrationPoses(nominal, 10, "joint");
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& p : poses) {
      for (int side = 0; side < 2; ++side) {
        CalibrationView v;
        v.info = info[side];
        const Eigen::Isometry3d cam_true = side == 0 ? truth.leftCamera(p.head) : truth.rightCamera(p.head);
        const Eigen::Isometry3d cam_nominal = side == 0 ? nominal.leftCamera(p.head) : nominal.rightCamera(p.head);
        v.truth = cam_true.inverse() * truth.marker(p.arm);
        v.predicted = cam_nominal.inverse() * nominal.marker(p.arm);
        render::RenderOptions o;
        o.noise_sigma = 1.5;
        o.blur_sigma = 0.6;
        o.background = 0.5;
        o.seed = static_cast<int>(views.size()) + 1;
        v.image = friend_hw_sim::renderView(renderer[side], world, plane, truth.marker(p.arm), cam_true, o);
        if (pass == 1 && u(rng) < 0.5) {
          // As the simulator's reflection fault: a third of the marker's size, within one side of it.
          const double side_px = info[side].K[0] * marker.size / v.truth.translation().z();
          const cv::Point2d c = renderer[side].camera().project(v.truth.translation());
          friend_hw_sim::addSpecularHighlight(v.image, c + cv::Point2d((u(rng) - 0.5) * side_px, (u(rng) - 0.5) * side_px),
                                              side_px * (0.12 + 0.15 * u(rng)), 200 + 100 * u(rng));
          v.reflection = true;
        }
        views.push_back(v);
      }
    }
  }
  return out;
}

}  // namespace imagenets_calibration
