// bench_sim_render: how fast the simulator renders a 1024x768 stereo pair of the calibration scene
// (gripper marker, table, boxes, floor, wall) from the true geometry, per supersampling factor,
// with both views rendered one after the other and side by side (as friend_sim does). Compared
// with what one calibration sample costs anyway: the arm/head motion to a new pose.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <camera_calibration_parsers/parse.h>

#include "friend_hw_sim/true_robot.h"
#include "friend_hw_sim/cameras.h"
#include "imagenets/vision/marker.h"
#include "friend_hw_sim/joint_trajectory.h"
#include "robot_description/robot_model.h"
#include "imagenets/package_file.h"
#include "imagenets/bench_summary.h"

using namespace friend_hw_sim;
using namespace robot_description;
namespace render = imagenets::render;
using Clock = std::chrono::steady_clock;

int main() {
  const std::string desc_path = imagenets::packageFile("friend_description", "config/robot.yaml");
  const auto nominal = loadRobotDescription(desc_path);
  const RobotModel truth(applyTrueError(nominal, loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), nominal)));
  const WorldScene world = loadWorldScene(imagenets::packageFile("friend_hw_sim", "config/scene.yaml"));
  const auto marker_desc = imagenets::marker::MarkerDescription::load(imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"));
  const render::Plane marker = imagenets::marker::markerPlane(marker_desc, Eigen::Isometry3d::Identity());
  sensor_msgs::CameraInfo li, ri;
  std::string name;
  camera_calibration_parsers::readCalibration(nominal.left_camera_info, name, li);
  camera_calibration_parsers::readCalibration(nominal.right_camera_info, name, ri);
  const auto& d = truth.description();
  const Eigen::Isometry3d m = truth.marker(d.arm_calibration_pose);
  const Eigen::Isometry3d lp = truth.leftCamera(d.head_calibration_pose), rp = truth.rightCamera(d.head_calibration_pose);
  std::printf("simulated stereo pair, 1024x768 mono8, %zu scene planes + the gripper marker, %u hardware threads\n",
              world.planes.size(), std::thread::hardware_concurrency());
  std::printf("full: the whole scene per frame; still: camera not moved since the last frame (the world\n"
              "is cached, only the marker is rendered over it); left and right render on two threads\n");
  std::printf("%-14s %10s %14s %14s %14s %16s %16s\n", "supersampling", "setup ms", "full pair ms", "full pairs/s",
              "still pair ms", "still pairs/s", "still/full speed");
  double pair_ms_default = 0;
  for (int ss : {1, 2, 3}) {
    const auto t0 = Clock::now();
    const render::Renderer left(render::CameraModel::fromCameraInfo(li), ss), right(render::CameraModel::fromCameraInfo(ri), ss);
    const double setup_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    render::RenderOptions o;
    o.noise_sigma = 1.5;
    o.blur_sigma = 0.6;
    auto pairMs = [&](int n, WorldViewCache* lc, WorldViewCache* rc) {
      const auto t1 = Clock::now();
      for (int i = 0; i < n; ++i) {
        o.seed = i + 1;
        std::thread other([&] { renderView(right, world, marker, m, rp, o, rc); });
        renderView(left, world, marker, m, lp, o, lc);
        other.join();
      }
      return std::chrono::duration<double, std::milli>(Clock::now() - t1).count() / n;
    };
    const int n = ss == 3 ? 3 : 6;
    const double full_ms = pairMs(n, nullptr, nullptr);
    WorldViewCache lc, rc;
    pairMs(1, &lc, &rc);  // fills the caches
    const double still_ms = pairMs(n * 3, &lc, &rc);
    std::printf("%-14d %10.0f %14.1f %14.2f %14.1f %16.2f %16.1f\n", ss, setup_ms, full_ms, 1000.0 / full_ms, still_ms,
                1000.0 / still_ms, full_ms / still_ms);
    const double par_ms = still_ms;
    if (ss == 2) pair_ms_default = par_ms;
  }
  // One calibration sample needs the arm and head at a pose: a motion of seconds.
  std::vector<double> vmax;
  for (const auto& j : d.arm.joints) vmax.push_back(j.max_velocity);
  const JointTrajectory move(d.arm_home, d.arm_calibration_pose, vmax, 1.0);
  std::printf("arm motion home -> calibration pose: %.2f s at time_scale 1, %.3f s at time_scale 10\n",
              move.duration(), move.duration() / 10);
  std::printf("default (supersampling 2, still camera) pair render / arm motion at time_scale 1: %.3f; at 10: %.3f\n",
              pair_ms_default / 1000 / move.duration(), pair_ms_default / 1000 / (move.duration() / 10));
  imagenets::printSummaryRow("simulator, stereo pair render ms (supersampling 2, still camera)", pair_ms_default, NAN, "",
                             false);
  return 0;
}
