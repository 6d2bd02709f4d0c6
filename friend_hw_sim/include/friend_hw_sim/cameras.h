// Simulated cameras of the FRIEND robot: the stereo camera on the pan-tilt head (left/right
// image_raw + camera_info, identical stamps), the hand camera on the gripper and, when the robot's
// description has one (head.mono_camera), a mono camera on the head. Images are
// rendered from the TRUE geometry (where the arm and head really are) with the shared renderer
// (imagenets/vision/render.h): the gripper marker on its plate, plus a textured table, boxes,
// floor and wall (config/friend/scene.yaml).
//
// Topics: stereo/{left,right}/{image_raw,camera_info}, hand_camera/{image_raw,camera_info},
// head_camera/{image_raw,camera_info} (the mono camera, at camera/rate);
// scene_markers (visualization_msgs/MarkerArray, latched: the world's planes for rviz);
// services stereo/trigger, hand_camera/trigger, head_camera/trigger (std_srvs/Trigger: render and
// publish now).
// Private parameters (read live unless noted):
//   camera/rate (Hz, 0 = only on trigger; default 5), hand_camera/rate (default 2),
//   camera/illumination (1.0), camera/noise (gray levels, 1.5), camera/blur (px, 0.6),
//   camera/color (false: mono8), camera/supersampling (at start, 2), scene (file, at start),
//   marker (marker description YAML, at start; default config/markers/gripper.yaml),
//   faults/drop_frame_probability, faults/corrupt_frame_probability,
//   faults/reflection_probability (a specular highlight near the marker: outlier detections),
//   faults/camera_silent (bool: no camera publishes anything, triggers answer failure; e.g. a
//   cable pulled for a while).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_srvs/Trigger.h>

#include "imagenets/vision/marker_scene.h"
#include "imagenets/vision/render.h"

namespace friend_hw_sim {

class FriendSim;
struct RobotState;

// A textured plane fixed in the world (base frame).
struct WorldPlane {
  std::string name;
  cv::Mat texture;
  double width = 1, height = 1, albedo = 1;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

struct WorldScene {
  std::vector<WorldPlane> planes;
  Eigen::Vector3d light_direction{0.4, 0.3, -1.0};
  double ambient = 0.45, diffuse = 0.55;
};

// Loads config/friend/scene.yaml; throws naming the file and key on bad input.
WorldScene loadWorldScene(const std::string& path);
// The static world as one camera saw it last (noise-free radiance and depth), so that a camera
// that has not moved re-renders only the gripper marker over it. Exact, not an approximation:
// the world is static, and when the world hides part of the marker the view is rendered in full.
struct WorldViewCache {
  bool valid = false;
  Eigen::Matrix4d camera_in_base = Eigen::Matrix4d::Zero();
  cv::Mat image;  // world only, illumination 1, no blur, no noise
  cv::Mat depth;  // CV_32F, 0 where nothing is hit
};

// Renders what one camera at `camera_in_base` sees: the world and the gripper marker plane
// (`marker_plane`: texture and size, e.g. imagenets::marker::markerPlane) at `marker_in_base`.
// With a cache, the world is rendered only when the camera moved.
cv::Mat renderView(const imagenets::render::Renderer& renderer, const WorldScene& world,
                   const imagenets::render::Plane& marker_plane, const Eigen::Isometry3d& marker_in_base,
                   const Eigen::Isometry3d& camera_in_base, const imagenets::render::RenderOptions& options,
                   WorldViewCache* cache = nullptr);

// A specular highlight (a lamp on the gripper's metal): the simulator's spurious-reflection fault;
// benchmarks and the marker study use it too.
using imagenets::marker::addSpecularHighlight;

class CameraSim {
 public:
  CameraSim(ros::NodeHandle nh, ros::NodeHandle pnh, const FriendSim& sim);
  ~CameraSim();

 private:
  struct Camera {
    std::string name, frame;
    sensor_msgs::CameraInfo info;
    std::unique_ptr<imagenets::render::Renderer> renderer;
    WorldViewCache cache;
    ros::Publisher image, camera_info;
  };
  void loop();
  void publishStereo();
  void publishHand();
  void publishMono();
  bool triggerStereo(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool triggerHand(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool triggerMono(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  imagenets::render::RenderOptions options(std::uint64_t seed);
  // faults/camera_silent is set.
  bool silent();
  // Applies the configured faults; returns false when the frame is dropped.
  bool applyFaults(cv::Mat& image, const Camera& cam, const Eigen::Isometry3d& camera_in_base,
                   const Eigen::Isometry3d& marker_in_base);
  void publish(Camera& cam, const cv::Mat& image, const ros::Time& stamp);
  Camera makeCamera(ros::NodeHandle nh, const std::string& name, const std::string& info_file,
                    const std::string& frame, int supersampling);

  ros::NodeHandle nh_, pnh_;
  const FriendSim& sim_;
  WorldScene world_;
  imagenets::render::Plane marker_plane_;  // pose set per frame
  double marker_size_ = 0.06;
  Camera left_, right_, hand_;
  std::unique_ptr<Camera> mono_;  // the head's mono camera, if the robot has one
  ros::ServiceServer trigger_stereo_, trigger_hand_, trigger_mono_;
  ros::Publisher scene_markers_;
  std::mutex render_mutex_, rng_mutex_;
  std::mt19937 rng_;
  std::uint64_t frame_ = 0;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

}  // namespace friend_hw_sim
