#include "friend_hw_sim/cameras.h"

#include <cmath>

#include <boost/make_shared.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/Image.h>
#include <visualization_msgs/MarkerArray.h>
#include <yaml-cpp/yaml.h>

#include "friend_hw_sim/friend_sim.h"
#include "imagenets/vision/frames.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/target.h"
#include "imagenets/vision/read_camera_info.h"
#include "imagenets/package_file.h"

namespace friend_hw_sim {

using robot_description::fromXyzRpy;
using robot_description::RobotModel;

namespace {

constexpr double kDeg = M_PI / 180.0;
namespace render = imagenets::render;

// Random blobs at several scales around `mean` with peak-to-peak about `contrast`: texture that
// stereo matching can lock onto at any distance.
cv::Mat blobTexture(int width, int height, double mean, double contrast, cv::RNG& rng) {
  cv::Mat acc = cv::Mat::zeros(height, width, CV_32F);
  double weight_sum = 0;
  for (int scale : {3, 9, 27, 81}) {
    cv::Mat small(std::max(2, height / scale), std::max(2, width / scale), CV_32F);
    rng.fill(small, cv::RNG::UNIFORM, -1.0, 1.0);
    cv::Mat big;
    cv::resize(small, big, acc.size(), 0, 0, cv::INTER_CUBIC);
    const double w = 1.0 / std::sqrt(static_cast<double>(scale));
    acc += big * w;
    weight_sum += w;
  }
  acc /= weight_sum;
  cv::Mat out;
  acc.convertTo(out, CV_8U, 255.0 * contrast, 255.0 * mean);
  return out;
}

std::vector<double> nums(const YAML::Node& n, const std::string& where, size_t size) {
  if (!n || !n.IsSequence() || n.size() != size) {
    throw std::runtime_error(where + ": expected a list of " + std::to_string(size) + " numbers");
  }
  std::vector<double> v;
  for (const auto& e : n) v.push_back(e.as<double>());
  return v;
}

Eigen::Isometry3d poseOf(const YAML::Node& n, const std::string& where) {
  const auto xyz = nums(n["xyz"], where + ".xyz", 3);
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (n["rpy_deg"]) {
    const auto r = nums(n["rpy_deg"], where + ".rpy_deg", 3);
    rpy = Eigen::Vector3d(r[0], r[1], r[2]) * kDeg;
  }
  return fromXyzRpy(Eigen::Vector3d(xyz[0], xyz[1], xyz[2]), rpy);
}

sensor_msgs::ImagePtr toImage(const cv::Mat& m, const std::string& frame, const ros::Time& stamp) {
  auto img = boost::make_shared<sensor_msgs::Image>();
  img->header.stamp = stamp;
  img->header.frame_id = frame;
  img->height = m.rows;
  img->width = m.cols;
  img->encoding = m.channels() == 3 ? "bgr8" : "mono8";
  img->step = static_cast<uint32_t>(m.cols * m.elemSize());
  img->data.resize(img->step * m.rows);
  for (int y = 0; y < m.rows; ++y) std::memcpy(&img->data[y * img->step], m.ptr(y), img->step);
  return img;
}

}  // namespace

WorldScene loadWorldScene(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("scene file '" + path + "': " + e.what());
  }
  WorldScene s;
  try {
    cv::RNG rng(root["seed"] ? root["seed"].as<int>() : 7);
    if (root["light_direction"]) {
      const auto l = nums(root["light_direction"], path + ": light_direction", 3);
      s.light_direction = Eigen::Vector3d(l[0], l[1], l[2]);
    }
    if (root["ambient"]) s.ambient = root["ambient"].as<double>();
    if (root["diffuse"]) s.diffuse = root["diffuse"].as<double>();
    for (size_t i = 0; root["planes"] && i < root["planes"].size(); ++i) {
      const YAML::Node p = root["planes"][i];
      const std::string w = path + ": planes[" + std::to_string(i) + "]";
      WorldPlane wp;
      wp.name = p["name"] ? p["name"].as<std::string>() : "plane_" + std::to_string(i);
      wp.pose = poseOf(p, w);
      const auto size = nums(p["size"], w + ".size", 2);
      wp.width = size[0];
      wp.height = size[1];
      std::vector<double> px{512, 512};
      if (p["texture_px"]) px = nums(p["texture_px"], w + ".texture_px", 2);
      wp.texture = blobTexture(static_cast<int>(px[0]), static_cast<int>(px[1]), p["mean"] ? p["mean"].as<double>() : 0.5,
                               p["contrast"] ? p["contrast"].as<double>() : 0.5, rng);
      s.planes.push_back(wp);
    }
    for (size_t i = 0; root["boxes"] && i < root["boxes"].size(); ++i) {
      const YAML::Node b = root["boxes"][i];
      const std::string w = path + ": boxes[" + std::to_string(i) + "]";
      const std::string name = b["name"] ? b["name"].as<std::string>() : "box_" + std::to_string(i);
      const auto xyz = nums(b["xyz"], w + ".xyz", 3);
      const auto size = nums(b["size"], w + ".size", 3);
      const double yaw = (b["yaw_deg"] ? b["yaw_deg"].as<double>() : 0.0) * kDeg;
      const double mean = b["mean"] ? b["mean"].as<double>() : 0.5, contrast = b["contrast"] ? b["contrast"].as<double>() : 0.7;
      const Eigen::Isometry3d centre =
          fromXyzRpy(Eigen::Vector3d(xyz[0], xyz[1], xyz[2] + size[2] / 2), Eigen::Vector3d(0, 0, yaw));
      const double hx = size[0] / 2, hy = size[1] / 2, hz = size[2] / 2;
      // Five faces (the bottom is on the table): offset along the face normal, z out of the box.
      struct Face { const char* tag; Eigen::Vector3d offset, rpy; double w, h; };
      const Face faces[] = {
          {"top", {0, 0, hz}, {0, 0, 0}, size[0], size[1]},
          {"front", {hx, 0, 0}, {0, M_PI / 2, 0}, size[2], size[1]},
          {"back", {-hx, 0, 0}, {0, -M_PI / 2, 0}, size[2], size[1]},
          {"left", {0, hy, 0}, {-M_PI / 2, 0, 0}, size[0], size[2]},
          {"right", {0, -hy, 0}, {M_PI / 2, 0, 0}, size[0], size[2]},
      };
      for (const Face& f : faces) {
        WorldPlane wp;
        wp.name = name + "/" + f.tag;
        wp.pose = centre * fromXyzRpy(f.offset, f.rpy);
        wp.width = f.w;
        wp.height = f.h;
        wp.texture = blobTexture(std::max(8, static_cast<int>(f.w * 1000)), std::max(8, static_cast<int>(f.h * 1000)),
                                 mean, contrast, rng);
        s.planes.push_back(wp);
      }
    }
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("scene file '" + path + "': " + e.what());
  }
  return s;
}

namespace {

render::Scene worldScene(const WorldScene& world, const Eigen::Isometry3d& base_in_camera) {
  render::Scene scene;
  scene.light.direction = base_in_camera.linear() * world.light_direction;
  scene.light.ambient = world.ambient;
  scene.light.diffuse = world.diffuse;
  for (const auto& wp : world.planes) {
    render::Plane p;
    p.texture = wp.texture;
    p.width = wp.width;
    p.height = wp.height;
    p.albedo = wp.albedo;
    p.pose = base_in_camera * wp.pose;
    scene.planes.push_back(p);
  }
  return scene;
}

}  // namespace

cv::Mat renderView(const render::Renderer& renderer, const WorldScene& world, const render::Plane& marker_plane,
                   const Eigen::Isometry3d& marker_in_base, const Eigen::Isometry3d& camera_in_base,
                   const render::RenderOptions& options, WorldViewCache* cache) {
  const Eigen::Isometry3d base_in_camera = camera_in_base.inverse();
  render::Scene scene = worldScene(world, base_in_camera);
  render::Plane marker = marker_plane;
  marker.pose = base_in_camera * marker_in_base;
  if (!cache) {
    scene.planes.push_back(marker);
    return renderer.render(scene, options);
  }
  if (!cache->valid || cache->camera_in_base != camera_in_base.matrix()) {
    render::RenderOptions plain = options;
    plain.illumination = 1.0;
    plain.blur_sigma = 0.0;
    plain.noise_sigma = 0.0;
    cache->image = renderer.render(scene, plain);
    cache->depth = renderer.renderDepth(scene);
    cache->camera_in_base = camera_in_base.matrix();
    cache->valid = true;
  }
  render::Scene marker_only;
  marker_only.light = scene.light;
  marker_only.planes.push_back(marker);
  // Where the world is nearer than the marker, the marker is (partly) hidden: render in full.
  const cv::Mat marker_depth = renderer.renderDepth(marker_only);
  const cv::Mat hit = marker_depth > 0;
  const cv::Mat world_hit = cache->depth > 0;
  cv::Mat in_front = (cache->depth < marker_depth) & hit & world_hit;
  if (cv::countNonZero(in_front) > 0) {
    scene.planes.push_back(marker);
    return renderer.render(scene, options);
  }
  render::RenderOptions over = options;
  over.background_image = cache->image;
  return renderer.render(marker_only, over);
}

CameraSim::Camera CameraSim::makeCamera(ros::NodeHandle nh, const std::string& name, const std::string& info_file,
                                        const std::string& frame, int supersampling) {
  Camera c;
  c.name = name;
  c.frame = frame;
  try {
    c.info = imagenets::readCameraInfo(info_file);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("camera '" + name + "': " + e.what());
  }
  c.info.header.frame_id = frame;
  c.renderer = std::make_unique<render::Renderer>(render::CameraModel::fromCameraInfo(c.info), supersampling);
  c.image = nh.advertise<sensor_msgs::Image>(name + "/image_raw", 2);
  c.camera_info = nh.advertise<sensor_msgs::CameraInfo>(name + "/camera_info", 2);
  return c;
}

CameraSim::CameraSim(ros::NodeHandle nh, ros::NodeHandle pnh, const FriendSim& sim)
    : nh_(nh), pnh_(pnh), sim_(sim), rng_(static_cast<unsigned>(pnh.param<int>("noise_seed", 1)) + 101) {
  world_ = loadWorldScene(pnh_.param<std::string>("scene", imagenets::packageFile("friend_hw_sim", "config/scene.yaml")));
  // What the gripper carries, as printed: ~target (a target file, config/targets/: the square
  // marker, AprilTags, a ChArUco board, its frame where the description puts the marker) or else
  // ~marker (config/markers/gripper.yaml: border, pattern, white margin).
  const auto& d = sim_.nominal().description();
  const std::string target_file = pnh_.param<std::string>("target", "");
  if (!target_file.empty()) {
    const auto target = imagenets::target::TargetDescription::load(target_file);
    if (target.type == imagenets::target::TargetType::SquareMarker && std::abs(target.size - d.marker_size) > 1e-9) {
      throw std::runtime_error("target '" + target_file + "' is a " + std::to_string(target.size) +
                               " m marker but the robot description's arm.marker.size is " + std::to_string(d.marker_size) + " m");
    }
    marker_plane_ = target.plane(Eigen::Isometry3d::Identity());
    marker_size_ = std::max(target.patternWidth(), target.patternHeight());
    ROS_INFO("friend_sim: the gripper carries %s (%s, %.0f x %.0f mm)", target_file.c_str(), target.typeName().c_str(),
             1000 * target.patternWidth(), 1000 * target.patternHeight());
  } else {
    const std::string marker_file =
        pnh_.param<std::string>("marker", imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"));
    const auto marker = imagenets::marker::MarkerDescription::load(marker_file);
    if (std::abs(marker.size - d.marker_size) > 1e-9) {
      throw std::runtime_error("marker '" + marker_file + "' is " + std::to_string(marker.size) +
                               " m but the robot description's arm.marker.size is " + std::to_string(d.marker_size) + " m");
    }
    marker_plane_ = imagenets::marker::markerPlane(marker, Eigen::Isometry3d::Identity());
    marker_size_ = marker.size;
  }
  const int ss = pnh_.param("camera/supersampling", 2);
  left_ = makeCamera(nh_, "stereo/left", d.left_camera_info, d.left_camera.frame, ss);
  right_ = makeCamera(nh_, "stereo/right", d.right_camera_info, d.right_camera_frame, ss);
  hand_ = makeCamera(nh_, "hand_camera", imagenets::packageFile("friend_description", "config/cameras/friend_hand_camera.yaml"), d.hand_camera.frame, ss);
  if (!d.mono_camera.frame.empty()) {
    mono_ = std::make_unique<Camera>(makeCamera(nh_, "head_camera", d.mono_camera_info, d.mono_camera.frame, ss));
    trigger_mono_ = nh_.advertiseService("head_camera/trigger", &CameraSim::triggerMono, this);
  }
  // The world's planes as thin boxes for rviz (latched: the world does not change).
  scene_markers_ = nh_.advertise<visualization_msgs::MarkerArray>("scene_markers", 1, true);
  visualization_msgs::MarkerArray markers;
  for (const auto& wp : world_.planes) {
    visualization_msgs::Marker mk;
    mk.header.frame_id = d.base_frame;
    mk.ns = "friend_sim_scene";
    mk.id = static_cast<int>(markers.markers.size());
    mk.type = visualization_msgs::Marker::CUBE;
    const Eigen::Isometry3d centre = wp.pose * fromXyzRpy(Eigen::Vector3d(0, 0, -0.001), Eigen::Vector3d::Zero());
    mk.pose = imagenets::frames::toPose(centre);
    mk.scale.x = wp.width;
    mk.scale.y = wp.height;
    mk.scale.z = 0.002;
    const float grey = static_cast<float>(cv::mean(wp.texture)[0] / 255.0);
    mk.color.r = grey * 0.9f;
    mk.color.g = grey * 0.8f;
    mk.color.b = grey * 0.6f;
    mk.color.a = wp.name == "floor" || wp.name == "wall" ? 0.35f : 1.0f;
    markers.markers.push_back(mk);
  }
  scene_markers_.publish(markers);
  trigger_stereo_ = nh_.advertiseService("stereo/trigger", &CameraSim::triggerStereo, this);
  trigger_hand_ = nh_.advertiseService("hand_camera/trigger", &CameraSim::triggerHand, this);
  thread_ = std::thread([this] { loop(); });
}

CameraSim::~CameraSim() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

render::RenderOptions CameraSim::options(std::uint64_t seed) {
  render::RenderOptions o;
  pnh_.getParamCached("camera/illumination", o.illumination);
  o.noise_sigma = 1.5;
  o.blur_sigma = 0.6;
  pnh_.getParamCached("camera/noise", o.noise_sigma);
  pnh_.getParamCached("camera/blur", o.blur_sigma);
  pnh_.getParamCached("camera/color", o.color);
  o.background = 0.5;
  o.seed = seed;
  return o;
}

bool CameraSim::applyFaults(cv::Mat& image, const Camera& cam, const Eigen::Isometry3d& camera_in_base,
                            const Eigen::Isometry3d& marker_in_base) {
  if (silent()) return false;
  double p_drop = 0, p_corrupt = 0, p_reflection = 0;
  pnh_.getParamCached("faults/drop_frame_probability", p_drop);
  pnh_.getParamCached("faults/corrupt_frame_probability", p_corrupt);
  pnh_.getParamCached("faults/reflection_probability", p_reflection);
  std::lock_guard<std::mutex> lock(rng_mutex_);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (u(rng_) < p_drop) return false;
  if (u(rng_) < p_reflection) {
    // A specular highlight near the marker, as from a lamp on the gripper's metal: a saturated
    // Gaussian spot of about a third of the marker's size, centred within one marker side of it.
    const Eigen::Vector3d c = (camera_in_base.inverse() * marker_in_base).translation();
    if (c.z() > 0.05) {
      const cv::Point2d px = cam.renderer->camera().project(c);
      const double side = cam.info.K[0] * marker_size_ / c.z();
      const cv::Point2d centre(px.x + (u(rng_) - 0.5) * side, px.y + (u(rng_) - 0.5) * side);
      const double sigma = side * (0.12 + 0.15 * u(rng_));
      const double amplitude = 200 + 100 * u(rng_);
      addSpecularHighlight(image, centre, sigma, amplitude);
    }
  }
  if (u(rng_) < p_corrupt) {
    // A transmission error: a band of rows shifted sideways and sprinkled with noise.
    const int h = static_cast<int>(image.rows * (0.1 + 0.2 * u(rng_)));
    const int y0 = static_cast<int>((image.rows - h) * u(rng_));
    const int shift = static_cast<int>(image.cols * (0.05 + 0.3 * u(rng_)));
    cv::Mat band = image.rowRange(y0, y0 + h);
    cv::Mat shifted;
    cv::hconcat(band.colRange(image.cols - shift, image.cols), band.colRange(0, image.cols - shift), shifted);
    cv::Mat noise(shifted.size(), shifted.type());
    cv::randu(noise, 0, 80);
    shifted += noise;
    shifted.copyTo(band);
  }
  return true;
}

void CameraSim::publish(Camera& cam, const cv::Mat& image, const ros::Time& stamp) {
  auto info = boost::make_shared<sensor_msgs::CameraInfo>(cam.info);
  info->header.stamp = stamp;
  cam.image.publish(toImage(image, cam.frame, stamp));
  cam.camera_info.publish(info);
}

void CameraSim::publishStereo() {
  std::lock_guard<std::mutex> lock(render_mutex_);
  const RobotState s = sim_.state();
  const auto truth_now = sim_.truth();  // one true robot for the whole frame
  const RobotModel& truth = *truth_now;
  const Eigen::Isometry3d marker = truth.marker(s.arm);
  const Eigen::Isometry3d left_pose = truth.leftCamera(s.head), right_pose = truth.rightCamera(s.head);
  const std::uint64_t seed = ++frame_ * 2;
  cv::Mat left, right;
  // The two views render in parallel (the renderer also splits rows across threads).
  std::thread right_thread(
      [&] { right = renderView(*right_.renderer, world_, marker_plane_, marker, right_pose, options(seed + 1), &right_.cache); });
  left = renderView(*left_.renderer, world_, marker_plane_, marker, left_pose, options(seed), &left_.cache);
  right_thread.join();
  if (applyFaults(left, left_, left_pose, marker)) publish(left_, left, s.stamp);
  if (applyFaults(right, right_, right_pose, marker)) publish(right_, right, s.stamp);
}

void CameraSim::publishHand() {
  std::lock_guard<std::mutex> lock(render_mutex_);
  const RobotState s = sim_.state();
  const auto truth_now = sim_.truth();  // one true robot for the whole frame
  const RobotModel& truth = *truth_now;
  const Eigen::Isometry3d marker = truth.marker(s.arm), cam = truth.handCamera(s.arm);
  cv::Mat image = renderView(*hand_.renderer, world_, marker_plane_, marker, cam, options(++frame_ * 2), &hand_.cache);
  if (applyFaults(image, hand_, cam, marker)) publish(hand_, image, s.stamp);
}

bool CameraSim::silent() {
  bool silent = false;
  pnh_.getParamCached("faults/camera_silent", silent);
  return silent;
}

bool CameraSim::triggerStereo(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  try {
    res.success = !silent();
    if (res.success) publishStereo();
    res.message = res.success ? "stereo pair published" : "stereo camera silent (fault: ~faults/camera_silent)";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("stereo camera: ") + e.what();
  }
  return true;
}

bool CameraSim::triggerMono(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  try {
    res.success = !silent();
    if (res.success) publishMono();
    res.message = res.success ? "head camera image published" : "head camera silent (fault: ~faults/camera_silent)";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("head camera: ") + e.what();
  }
  return true;
}

void CameraSim::publishMono() {
  std::lock_guard<std::mutex> lock(render_mutex_);
  const RobotState s = sim_.state();
  const auto truth_now = sim_.truth();  // one true robot for the whole frame
  const Eigen::Isometry3d marker = truth_now->marker(s.arm), cam = truth_now->monoCamera(s.head);
  cv::Mat image = renderView(*mono_->renderer, world_, marker_plane_, marker, cam, options(++frame_ * 2), &mono_->cache);
  if (applyFaults(image, *mono_, cam, marker)) publish(*mono_, image, s.stamp);
}

bool CameraSim::triggerHand(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  try {
    res.success = !silent();
    if (res.success) publishHand();
    res.message = res.success ? "hand camera image published" : "hand camera silent (fault: ~faults/camera_silent)";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("hand camera: ") + e.what();
  }
  return true;
}

void CameraSim::loop() {
  ros::Time next_stereo = ros::Time::now(), next_hand = ros::Time::now();
  while (running_ && ros::ok()) {
    double stereo_rate = 5.0, hand_rate = 2.0;
    pnh_.getParamCached("camera/rate", stereo_rate);
    pnh_.getParamCached("hand_camera/rate", hand_rate);
    const ros::Time now = ros::Time::now();
    try {
      if (stereo_rate > 0 && now >= next_stereo) {
        next_stereo = now + ros::Duration(1.0 / stereo_rate);
        if (left_.image.getNumSubscribers() + right_.image.getNumSubscribers() > 0) publishStereo();
        if (mono_ && mono_->image.getNumSubscribers() > 0) publishMono();
      }
      if (hand_rate > 0 && now >= next_hand) {
        next_hand = now + ros::Duration(1.0 / hand_rate);
        if (hand_.image.getNumSubscribers() > 0) publishHand();
      }
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5, "friend_sim cameras: %s", e.what());
    }
    ros::WallDuration(0.005).sleep();
  }
}

}  // namespace friend_hw_sim
