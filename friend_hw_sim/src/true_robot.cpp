#include "friend_hw_sim/true_robot.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "robot_description/yaml_fields.h"

namespace friend_hw_sim {

using robot_description::KinematicChain;
using robot_description::fromXyzRpy;
using robot_description::RobotDescription;
using namespace robot_description::yaml_fields;

TrueRobotError trueErrorFromYaml(const YAML::Node& node, const std::string& where, const RobotDescription& nominal,
                                 int seed_override, double magnitude) {
  if (!(magnitude > 0) || !std::isfinite(magnitude)) {
    throw std::runtime_error(where + ": the magnitude factor of the random error must be positive, not " +
                             std::to_string(magnitude));
  }
  TrueRobotError e;
  if (!node || node.IsNull()) return e;
  if (!node.IsMap()) throw error(where, "expected a map of true-robot error settings");
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
  const double head_t = magnitude * numberOr(mag, "head_mount_translation", 0.015, where + ".random");
  const double head_r = magnitude * numberOr(mag, "head_mount_rotation_deg", 2.0, where + ".random") * kDeg;
  const double marker_t = magnitude * numberOr(mag, "marker_translation", 0.001, where + ".random");
  const double marker_r = magnitude * numberOr(mag, "marker_rotation_deg", 0.5, where + ".random") * kDeg;
  const double joint = magnitude * numberOr(mag, "joint_offset_deg", 0.1, where + ".random") * kDeg;
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
  // One offset per joint of the robot's chains (drawn in this order: a seed's mount and marker
  // errors do not depend on the number of joints).
  for (size_t i = 0; i < nominal.arm.joints.size(); ++i) e.arm_joint_offsets.push_back(uni(rng) * joint);
  for (size_t i = 0; i < nominal.head.joints.size(); ++i) e.head_joint_offsets.push_back(uni(rng) * joint);
  return e;
}

TrueRobotError loadTrueError(const std::string& path, const RobotDescription& nominal, int seed_override,
                             double magnitude) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("true-robot error file '" + path + "': " + e.what());
  }
  const YAML::Node node = root["true_error"] ? root["true_error"] : root;
  return trueErrorFromYaml(node, path + ": true_error", nominal, seed_override, magnitude);
}

RobotDescription applyTrueError(const RobotDescription& nominal, const TrueRobotError& e) {
  RobotDescription t = nominal;
  t.head.mount = fromXyzRpy(nominal.head.mount.translation() + e.head_mount_xyz, Eigen::Vector3d::Zero()) *
                 fromXyzRpy(Eigen::Vector3d::Zero(), e.head_mount_rpy) *
                 Eigen::Isometry3d(nominal.head.mount.linear());
  t.marker.pose = nominal.marker.pose * fromXyzRpy(e.marker_xyz, e.marker_rpy);
  auto add = [](KinematicChain& c, const std::vector<double>& offsets, const char* what) {
    if (offsets.empty()) return;
    if (offsets.size() != c.joints.size()) {
      throw std::runtime_error(std::string("true-robot error: ") + what + " has " + std::to_string(offsets.size()) +
                               " joint offsets, the chain has " + std::to_string(c.joints.size()) + " joints");
    }
    for (size_t i = 0; i < offsets.size(); ++i) c.joints[i].offset += offsets[i];
  };
  add(t.arm, e.arm_joint_offsets, "arm_joint_offsets_deg");
  add(t.head, e.head_joint_offsets, "head_joint_offsets_deg");
  return t;
}

namespace {

// A zero offset `delta` of a chain's first joint, seen from the base: the motion of that joint by
// delta about (along) its axis, in the joint's frame at the mount.
Eigen::Isometry3d firstJointOffsetMotion(const robot_description::KinematicChain& chain, double delta) {
  const auto& j = chain.joints.front();
  const Eigen::Isometry3d pivot = chain.mount * j.origin;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  if (j.prismatic) {
    motion.translation() = j.axis * delta;
  } else {
    motion.linear() = Eigen::AngleAxisd(delta, j.axis.normalized()).toRotationMatrix();
  }
  return pivot * motion * pivot.inverse();
}

}  // namespace

Eigen::Isometry3d effectiveHeadBase(const RobotDescription& nominal, const TrueRobotError& error) {
  const RobotDescription truth = applyTrueError(nominal, error);
  if (error.head_joint_offsets.empty() || truth.head.joints.empty()) return truth.head.mount;
  // The pan offset turns everything after the mount: folded into it.
  return firstJointOffsetMotion(truth.head, error.head_joint_offsets[0]) * truth.head.mount;
}

Eigen::Isometry3d identifiableHeadBase(const RobotDescription& nominal, const TrueRobotError& error) {
  const Eigen::Isometry3d effective = effectiveHeadBase(nominal, error);
  if (error.arm_joint_offsets.empty() || nominal.arm.joints.empty()) return effective;
  // The true arm stands at encoder angle + offset: the nominal model puts the marker moved back by
  // the offset about joint 1's axis, and a fit of the head follows it.
  return firstJointOffsetMotion(nominal.arm, -error.arm_joint_offsets[0]) * effective;
}

}  // namespace friend_hw_sim
