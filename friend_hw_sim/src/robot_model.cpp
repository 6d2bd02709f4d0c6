#include "friend_hw_sim/robot_model.h"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include <boost/filesystem.hpp>
#include <ros/package.h>
#include <yaml-cpp/yaml.h>

namespace friend_hw_sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::runtime_error err(const std::string& where, const std::string& what) {
  return std::runtime_error(where + ": " + what);
}

const YAML::Node need(const YAML::Node& node, const std::string& key, const std::string& where) {
  if (!node.IsMap() || !node[key]) throw err(where, "missing key '" + key + "'");
  return node[key];
}

double number(const YAML::Node& node, const std::string& key, const std::string& where) {
  const YAML::Node v = need(node, key, where);
  try {
    return v.as<double>();
  } catch (const YAML::Exception&) {
    throw err(where + "." + key, "expected a number, got '" + YAML::Dump(v) + "'");
  }
}

double numberOr(const YAML::Node& node, const std::string& key, double fallback, const std::string& where) {
  return node.IsMap() && node[key] ? number(node, key, where) : fallback;
}

std::vector<double> numbers(const YAML::Node& v, const std::string& where, size_t expected_size) {
  if (!v.IsSequence()) throw err(where, "expected a list of numbers");
  std::vector<double> out;
  for (const auto& e : v) {
    try {
      out.push_back(e.as<double>());
    } catch (const YAML::Exception&) {
      throw err(where, "expected a number, got '" + YAML::Dump(e) + "'");
    }
  }
  if (expected_size && out.size() != expected_size) {
    throw err(where, "expected " + std::to_string(expected_size) + " numbers, got " + std::to_string(out.size()));
  }
  return out;
}

Eigen::Vector3d vec3(const YAML::Node& node, const std::string& key, const std::string& where, double scale = 1.0) {
  if (!node.IsMap() || !node[key]) return Eigen::Vector3d::Zero();
  auto v = numbers(node[key], where + "." + key, 3);
  return Eigen::Vector3d(v[0], v[1], v[2]) * scale;
}

FixedFrame fixedFrame(const YAML::Node& node, const std::string& where, const std::string& default_frame) {
  if (!node.IsMap()) throw err(where, "expected a map with xyz and rpy_deg");
  FixedFrame f;
  f.frame = node["frame"] ? node["frame"].as<std::string>() : default_frame;
  f.pose = fromXyzRpy(vec3(node, "xyz", where), vec3(node, "rpy_deg", where, kDeg));
  return f;
}

DhChain chain(const YAML::Node& node, const std::string& where) {
  DhChain c;
  c.link_prefix = node["link_prefix"] ? node["link_prefix"].as<std::string>() : where + "_link_";
  c.mount = fixedFrame(need(node, "mount", where), where + ".mount", "").pose;
  const YAML::Node joints = need(node, "joints", where);
  if (!joints.IsSequence() || joints.size() == 0) throw err(where + ".joints", "expected a non-empty list");
  for (size_t i = 0; i < joints.size(); ++i) {
    const std::string w = where + ".joints[" + std::to_string(i) + "]";
    const YAML::Node j = joints[i];
    DhJoint dh;
    dh.name = need(j, "name", w).as<std::string>();
    dh.a = number(j, "a", w);
    dh.d = number(j, "d", w);
    dh.alpha = number(j, "alpha_deg", w) * kDeg;
    dh.theta_offset = numberOr(j, "theta_offset_deg", 0.0, w) * kDeg;
    dh.min = number(j, "min_deg", w) * kDeg;
    dh.max = number(j, "max_deg", w) * kDeg;
    dh.max_velocity = number(j, "max_velocity_deg", w) * kDeg;
    if (!(dh.min < dh.max)) throw err(w, "min_deg must be below max_deg");
    if (!(dh.max_velocity > 0)) throw err(w, "max_velocity_deg must be positive");
    c.joints.push_back(dh);
  }
  return c;
}

std::vector<double> poseDeg(const YAML::Node& node, const std::string& key, const std::string& where, const DhChain& c) {
  if (!node[key]) return std::vector<double>(c.joints.size(), 0.0);
  auto v = numbers(node[key], where + "." + key, c.joints.size());
  for (double& x : v) x *= kDeg;
  const std::string bad = c.limitViolation(v);
  if (!bad.empty()) throw err(where + "." + key, bad);
  return v;
}

}  // namespace

Eigen::Isometry3d dhTransform(const DhJoint& j, double q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.rotate(Eigen::AngleAxisd(q + j.theta_offset, Eigen::Vector3d::UnitZ()));
  t.translate(Eigen::Vector3d(j.a, 0, j.d));  // Tz(d) Tx(a) commute
  t.rotate(Eigen::AngleAxisd(j.alpha, Eigen::Vector3d::UnitX()));
  return t;
}

Eigen::Isometry3d fromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = xyz;
  t.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return t;
}

Eigen::Vector3d rpyOf(const Eigen::Matrix3d& r) {
  // R = Rz(y) Ry(p) Rx(r): r20 = -sin p.
  const double pitch = std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0)));
  if (std::hypot(r(0, 0), r(1, 0)) < 1e-9) {  // gimbal lock: put all of yaw+-roll into yaw
    const double yaw = std::atan2(-r(0, 1), r(1, 1));
    return Eigen::Vector3d(0.0, pitch, yaw);
  }
  return Eigen::Vector3d(std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0)));
}

std::vector<std::string> DhChain::names() const {
  std::vector<std::string> n;
  for (const auto& j : joints) n.push_back(j.name);
  return n;
}

std::vector<Eigen::Isometry3d> DhChain::linkFrames(const std::vector<double>& q) const {
  if (q.size() != joints.size()) {
    throw std::invalid_argument("forward kinematics of '" + link_prefix + "*': expected " +
                                std::to_string(joints.size()) + " joint angles, got " + std::to_string(q.size()));
  }
  std::vector<Eigen::Isometry3d> frames{mount};
  for (size_t i = 0; i < joints.size(); ++i) frames.push_back(frames.back() * dhTransform(joints[i], q[i]));
  return frames;
}

std::string DhChain::limitViolation(const std::vector<double>& q) const {
  if (q.size() != joints.size()) {
    return "expected " + std::to_string(joints.size()) + " joint positions, got " + std::to_string(q.size());
  }
  for (size_t i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q[i]) || q[i] < joints[i].min - 1e-9 || q[i] > joints[i].max + 1e-9) {
      std::ostringstream s;
      s << "joint '" << joints[i].name << "' target " << q[i] << " rad (" << q[i] / kDeg
        << " deg) is outside its limits [" << joints[i].min / kDeg << ", " << joints[i].max / kDeg << "] deg";
      return s.str();
    }
  }
  return "";
}

RobotDescription loadRobotDescription(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw std::runtime_error("robot description '" + path + "': cannot read the file");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("robot description '" + path + "': " + e.what());
  }
  const std::string w = path;
  RobotDescription d;
  d.source = path;
  try {
    if (root["base_frame"]) d.base_frame = root["base_frame"].as<std::string>();
    const YAML::Node arm = need(root, "arm", w);
    d.arm = chain(arm, w + ": arm");
    d.tool = fixedFrame(need(arm, "tool", w + ": arm"), w + ": arm.tool", "tcp");
    const YAML::Node marker = need(arm, "marker", w + ": arm");
    d.marker = fixedFrame(marker, w + ": arm.marker", "gripper_marker");
    d.marker_size = number(marker, "size", w + ": arm.marker");
    if (!(d.marker_size > 0)) throw err(w + ": arm.marker.size", "must be positive");
    d.hand_camera = fixedFrame(need(arm, "hand_camera", w + ": arm"), w + ": arm.hand_camera", "hand_camera_optical_frame");
    d.ft_sensor = fixedFrame(need(arm, "ft_sensor", w + ": arm"), w + ": arm.ft_sensor", "ft_sensor");
    d.arm_calibration_pose = poseDeg(arm, "calibration_pose_deg", w + ": arm", d.arm);
    d.arm_home = poseDeg(arm, "home_deg", w + ": arm", d.arm);

    const YAML::Node head = need(root, "head", w);
    d.head = chain(head, w + ": head");
    if (d.head.joints.size() != 2) throw err(w + ": head.joints", "a pan-tilt head has exactly 2 joints");
    const YAML::Node stereo = need(head, "stereo_camera", w + ": head");
    const std::string ws = w + ": head.stereo_camera";
    d.left_camera = fixedFrame(need(stereo, "left", ws), ws + ".left", "");
    d.left_camera.frame = stereo["left_frame"] ? stereo["left_frame"].as<std::string>() : "stereo_left_optical_frame";
    if (stereo["right_frame"]) d.right_camera_frame = stereo["right_frame"].as<std::string>();
    d.stereo_baseline = number(stereo, "baseline", ws);
    d.image_width = static_cast<int>(numberOr(stereo, "width", 1024, ws));
    d.image_height = static_cast<int>(numberOr(stereo, "height", 768, ws));
    const auto dir = boost::filesystem::path(path).parent_path();
    auto rel = [&](const char* key) {
      if (!stereo[key]) return std::string();
      return (dir / stereo[key].as<std::string>()).lexically_normal().string();
    };
    d.left_camera_info = rel("left_camera_info");
    d.right_camera_info = rel("right_camera_info");
    d.head_calibration_pose = poseDeg(head, "calibration_pose_deg", w + ": head", d.head);
    d.head_home = poseDeg(head, "home_deg", w + ": head", d.head);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(w + ": " + e.what());
  }
  return d;
}

std::string defaultRobotDescriptionPath() {
  // The installed/sourced package first; else the source tree this library was built from.
  const std::string pkg = ros::package::getPath("imagenets");
  if (!pkg.empty() && boost::filesystem::exists(pkg + "/config/friend/robot.yaml")) {
    return pkg + "/config/friend/robot.yaml";
  }
  return std::string(FRIEND_HW_SIM_SOURCE_DIR) + "/config/friend/robot.yaml";
}

Eigen::Isometry3d RobotModel::tcp(const std::vector<double>& q) const { return d_.arm.end(q) * d_.tool.pose; }
Eigen::Isometry3d RobotModel::marker(const std::vector<double>& q) const { return tcp(q) * d_.marker.pose; }
Eigen::Isometry3d RobotModel::handCamera(const std::vector<double>& q) const { return tcp(q) * d_.hand_camera.pose; }
Eigen::Isometry3d RobotModel::ftSensor(const std::vector<double>& q) const { return d_.arm.end(q) * d_.ft_sensor.pose; }
Eigen::Isometry3d RobotModel::leftCamera(const std::vector<double>& q) const {
  return d_.head.end(q) * d_.left_camera.pose;
}
Eigen::Isometry3d RobotModel::leftToRight() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(d_.stereo_baseline, 0, 0);
  return t;
}
Eigen::Isometry3d RobotModel::rightCamera(const std::vector<double>& q) const { return leftCamera(q) * leftToRight(); }

std::array<double, 2> RobotModel::lookAt(const Eigen::Vector3d& target, std::array<double, 2> start) const {
  Eigen::Isometry3d centre_in_left = Eigen::Isometry3d::Identity();
  centre_in_left.translation() = Eigen::Vector3d(d_.stereo_baseline / 2, 0, 0);
  // Residual: the target's direction in the centre camera, (x/z, y/z); zero when centred.
  auto residual = [&](const Eigen::Vector2d& pt) {
    const Eigen::Vector3d p = (leftCamera({pt[0], pt[1]}) * centre_in_left).inverse() * target;
    return Eigen::Vector2d(std::atan2(p.x(), p.z()), std::atan2(p.y(), p.z()));
  };
  Eigen::Vector2d x(start[0], start[1]);
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector2d r = residual(x);
    if (r.norm() < 1e-12) break;
    Eigen::Matrix2d j;
    const double h = 1e-7;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d xp = x;
      xp[k] += h;
      j.col(k) = (residual(xp) - r) / h;
    }
    Eigen::Vector2d step = j.colPivHouseholderQr().solve(-r);
    if (!step.allFinite()) break;
    if (step.norm() > 0.5) step *= 0.5 / step.norm();
    x += step;
    for (int k = 0; k < 2; ++k) x[k] = std::min(std::max(x[k], d_.head.joints[k].min), d_.head.joints[k].max);
  }
  return {x[0], x[1]};
}

TrueRobotError trueErrorFromYaml(const YAML::Node& node, const std::string& where, int seed_override) {
  TrueRobotError e;
  if (!node || node.IsNull()) return e;
  if (!node.IsMap()) throw err(where, "expected a map of true-robot error settings");
  const int seed = seed_override >= 0 ? seed_override : static_cast<int>(numberOr(node, "seed", 0, where));
  auto offsets = [&](const char* key) {
    if (!node[key]) return std::vector<double>();
    auto v = numbers(node[key], where + "." + key, 0);
    for (double& x : v) x *= kDeg;
    return v;
  };
  if (seed <= 0) {
    e.head_mount_xyz = vec3(node, "head_mount_xyz", where);
    e.head_mount_rpy = vec3(node, "head_mount_rpy_deg", where, kDeg);
    e.marker_xyz = vec3(node, "marker_xyz", where);
    e.marker_rpy = vec3(node, "marker_rpy_deg", where, kDeg);
    e.arm_joint_offsets = offsets("arm_joint_offsets_deg");
    e.head_joint_offsets = offsets("head_joint_offsets_deg");
    return e;
  }
  // Random error of the given magnitudes: a direction uniformly on the sphere times the magnitude
  // for the mounts, uniform in +-magnitude for joint offsets.
  const YAML::Node mag = node["random"];
  const double head_t = numberOr(mag, "head_mount_translation", 0.015, where + ".random");
  const double head_r = numberOr(mag, "head_mount_rotation_deg", 2.0, where + ".random") * kDeg;
  const double marker_t = numberOr(mag, "marker_translation", 0.001, where + ".random");
  const double marker_r = numberOr(mag, "marker_rotation_deg", 0.5, where + ".random") * kDeg;
  const double joint = numberOr(mag, "joint_offset_deg", 0.1, where + ".random") * kDeg;
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  auto direction = [&] {
    Eigen::Vector3d v(gauss(rng), gauss(rng), gauss(rng));
    return Eigen::Vector3d(v.normalized());
  };
  e.head_mount_xyz = direction() * head_t;
  e.head_mount_rpy = direction() * head_r;
  e.marker_xyz = direction() * marker_t;
  e.marker_rpy = direction() * marker_r;
  for (int i = 0; i < 7; ++i) e.arm_joint_offsets.push_back(uni(rng) * joint);
  for (int i = 0; i < 2; ++i) e.head_joint_offsets.push_back(uni(rng) * joint);
  return e;
}

TrueRobotError loadTrueError(const std::string& path, int seed_override) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("true-robot error file '" + path + "': " + e.what());
  }
  const YAML::Node node = root["true_error"] ? root["true_error"] : root;
  return trueErrorFromYaml(node, path + ": true_error", seed_override);
}

RobotDescription applyTrueError(const RobotDescription& nominal, const TrueRobotError& e) {
  RobotDescription t = nominal;
  t.head.mount = fromXyzRpy(nominal.head.mount.translation() + e.head_mount_xyz, Eigen::Vector3d::Zero()) *
                 fromXyzRpy(Eigen::Vector3d::Zero(), e.head_mount_rpy) *
                 Eigen::Isometry3d(nominal.head.mount.linear());
  t.marker.pose = nominal.marker.pose * fromXyzRpy(e.marker_xyz, e.marker_rpy);
  auto add = [](DhChain& c, const std::vector<double>& offsets, const char* what) {
    if (offsets.empty()) return;
    if (offsets.size() != c.joints.size()) {
      throw std::runtime_error(std::string("true-robot error: ") + what + " has " + std::to_string(offsets.size()) +
                               " joint offsets, the chain has " + std::to_string(c.joints.size()) + " joints");
    }
    for (size_t i = 0; i < offsets.size(); ++i) c.joints[i].theta_offset += offsets[i];
  };
  add(t.arm, e.arm_joint_offsets, "arm_joint_offsets_deg");
  add(t.head, e.head_joint_offsets, "head_joint_offsets_deg");
  return t;
}

}  // namespace friend_hw_sim
