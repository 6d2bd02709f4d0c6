#include "robot_description/robot_model.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <boost/filesystem.hpp>
#include <ros/package.h>
#include <ros/names.h>
#include <ros/ros.h>
#include <yaml-cpp/yaml.h>

#include "robot_description/urdf_kinematics.h"
#include "robot_description/urdf_writer.h"
#include "robot_description/yaml_fields.h"

namespace robot_description {
namespace {

using namespace yaml_fields;
using yaml_fields::error;

FixedFrame fixedFrame(const YAML::Node& node, const std::string& where, const std::string& default_frame) {
  if (!node.IsMap()) throw error(where, "expected a map with xyz and rpy_deg");
  FixedFrame f;
  f.frame = node["frame"] ? node["frame"].as<std::string>() : default_frame;
  f.pose = fromXyzRpy(vec3(node, "xyz", where), vec3(node, "rpy_deg", where, kDeg));
  return f;
}

KinematicChain chain(const YAML::Node& node, const std::string& where) {
  KinematicChain c;
  c.link_prefix = node["link_prefix"] ? node["link_prefix"].as<std::string>() : where + "_link_";
  c.mount = fixedFrame(need(node, "mount", where), where + ".mount", "").pose;
  const YAML::Node joints = need(node, "joints", where);
  if (!joints.IsSequence() || joints.size() == 0) throw error(where + ".joints", "expected a non-empty list");
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
    if (!(dh.min < dh.max)) throw error(w, "min_deg must be below max_deg");
    if (!(dh.max_velocity > 0)) throw error(w, "max_velocity_deg must be positive");
    c.joints.push_back(fromDh(dh));
  }
  return c;
}

std::vector<double> poseDeg(const YAML::Node& node, const std::string& key, const std::string& where, const KinematicChain& c) {
  if (!node[key]) return std::vector<double>(c.joints.size(), 0.0);
  auto v = numbers(node[key], where + "." + key, c.joints.size());
  for (double& x : v) x *= kDeg;
  const std::string bad = c.limitViolation(v);
  if (!bad.empty()) throw error(where + "." + key, bad);
  return v;
}

// The key free_params (freeParams), checked against the description's joints.
void readFreeParams(const YAML::Node& root, RobotDescription& d) {
  const YAML::Node p = root["free_params"];
  if (!p) return;
  if (!p.IsSequence() || p.size() == 0) {
    throw error(d.source + ": free_params", "expected a non-empty list of parameter names");
  }
  d.free_params = p.as<std::vector<std::string>>();
  freeParams(d);
}

// An interface's name (key `key` of `node`, at `where`) into `out`: a string that is a valid ROS
// graph name; absent: "" (the nets' own name holds).
void readInterfaceName(const YAML::Node& node, const std::string& key, const std::string& where, std::string& out) {
  if (!node.IsMap() || !node[key]) return;
  const YAML::Node v = node[key];
  if (!v.IsScalar() || v.Scalar().empty()) {
    throw error(where + "." + key, "expected a ROS name (e.g. arm_controller/follow_joint_trajectory), got '" +
                                       YAML::Dump(v) + "'");
  }
  std::string why;
  if (!ros::names::validate(v.Scalar(), why)) throw error(where + "." + key, "'" + v.Scalar() + "' is no valid ROS name: " + why);
  out = v.Scalar();
}

// The keys naming the robot's interfaces (RobotDescription::arm_controller, ...), in either form.
void readInterfaces(const YAML::Node& root, const std::string& w, RobotDescription& d) {
  readInterfaceName(root["arm"], "controller", w + ": arm", d.arm_controller);
  readInterfaceName(root["head"], "controller", w + ": head", d.head_controller);
  if (root["head"]) readInterfaceName(root["head"]["stereo_camera"], "namespace", w + ": head.stereo_camera", d.stereo_namespace);
  if (root["head"] && root["head"]["mono_camera"]) {
    readInterfaceName(root["head"]["mono_camera"], "namespace", w + ": head.mono_camera", d.mono_namespace);
  }
}

// The file that `node`'s key `key` names, relative to the folder of the YAML file `yaml`; "" without
// the key.
std::string fileNamedBy(const YAML::Node& node, const char* key, const std::string& yaml) {
  if (!node[key]) return "";
  return (boost::filesystem::path(yaml).parent_path() / node[key].as<std::string>()).lexically_normal().string();
}

// The YAML file `d` was read from, when it is still there and a map; a null node otherwise (a
// description made in code, or a file loadRobotDescription would have refused).
YAML::Node descriptionYaml(const RobotDescription& d) {
  if (d.source.empty() || !boost::filesystem::exists(d.source)) return YAML::Node();
  YAML::Node root;
  try {
    root = YAML::LoadFile(d.source);
  } catch (const YAML::Exception&) {
    return YAML::Node();
  }
  return root.IsMap() ? root : YAML::Node();
}

std::string& urdfFileForAll() {
  static std::string path;
  return path;
}

// The URDF form names links (arm.tip_link, ...) where the DH form lists joints (arm.joints).
bool urdfForm(const YAML::Node& root) { return root["urdf"] || !(root["arm"] && root["arm"]["joints"]); }

// The URDF text of a description in the URDF form (root) and where it is from (loadRobotDescription).
std::string urdfText(const YAML::Node& root, const std::string& path, std::string& source);

// The URDF on the parameter server, as urdf::Model::initParam and robot_state_publisher read it.
std::string urdfFromParameter(const std::string& where, std::string& source) {
  const std::string why = "names no URDF file (key 'urdf')";
  if (!ros::isInitialized()) {
    throw error(where, why + " and this program is no ROS node to read the parameter robot_description: give the "
                             "file (urdf: FILE, or the command's --urdf FILE)");
  }
  ros::NodeHandle nh;
  std::string key, xml;
  if (!nh.searchParam("robot_description", key) || !nh.getParam(key, xml)) {
    throw error(where, why + " and the parameter robot_description is not set (searched from the namespace '" +
                           nh.getNamespace() + "' up)");
  }
  source = "parameter " + key;
  return xml;
}

std::string urdfText(const YAML::Node& root, const std::string& path, std::string& source) {
  if (root["urdf"] && root["urdf"].as<std::string>() != "robot_description") {
    source = fileNamedBy(root, "urdf", path);
  } else if (!urdfFileForAll().empty()) {
    source = urdfFileForAll();
  } else {
    return urdfFromParameter(path, source);
  }
  std::ifstream in(source);
  if (!in) throw std::runtime_error("URDF '" + source + "': cannot read the file (named by " + path + ")");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Throws naming the key when `node` (at `where`) has a key not among `known`: a misspelt key would
// otherwise be ignored silently (free_parms: the calibration estimating everything).
void onlyKnownKeys(const YAML::Node& node, const std::vector<std::string>& known, const std::string& where) {
  if (!node.IsMap()) throw error(where, "expected a map");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw error(where, "unknown key '" + key + "' (known: " + list + ")");
  }
}

// The keys of the URDF form, checked before anything is read.
void checkUrdfFormKeys(const YAML::Node& root, const std::string& w) {
  onlyKnownKeys(root, {"urdf", "name", "base_frame", "free_params", "arm", "head"}, w);
  const YAML::Node arm = need(root, "arm", w), head = need(root, "head", w);
  onlyKnownKeys(arm, {"tip_link", "tool_link", "marker", "hand_camera_link", "ft_sensor_link", "calibration_pose_deg",
                      "home_deg", "link_prefix", "controller"},
                w + ": arm");
  onlyKnownKeys(need(arm, "marker", w + ": arm"), {"link", "size"}, w + ": arm.marker");
  onlyKnownKeys(head, {"tip_link", "stereo_camera", "mono_camera", "calibration_camera", "calibration_pose_deg", "home_deg",
                       "link_prefix", "controller"},
                w + ": head");
  onlyKnownKeys(need(head, "stereo_camera", w + ": head"),
                {"left_link", "right_link", "width", "height", "left_camera_info", "right_camera_info", "namespace"},
                w + ": head.stereo_camera");
  if (head["mono_camera"]) onlyKnownKeys(head["mono_camera"], {"link", "camera_info", "namespace"}, w + ": head.mono_camera");
}

// What both forms read alike once the chains are known: the head's poses, the interfaces, the
// free parameters and the camera to calibrate.
void readHeadPosesAndSettings(const YAML::Node& root, const std::string& w, RobotDescription& d) {
  const YAML::Node head = need(root, "head", w);
  d.head_calibration_pose = poseDeg(head, "calibration_pose_deg", w + ": head", d.head);
  d.head_home = poseDeg(head, "home_deg", w + ": head", d.head);
  readInterfaces(root, w, d);
  readFreeParams(root, d);
  if (head["calibration_camera"]) {
    d = withCalibrationCamera(d, head["calibration_camera"].as<std::string>(), w + ": head.calibration_camera");
  }
}

// A description whose kinematics are a URDF's (urdf_kinematics.h): the URDF (loadRobotDescription)
// and the links to read; the rest as in a DH description.
RobotDescription fromUrdf(const YAML::Node& root, const std::string& path) {
  const std::string w = path;
  RobotDescription d;
  d.source = path;
  try {
    checkUrdfFormKeys(root, w);
    std::string source;
    const std::string xml = urdfText(root, path, source);
    const UrdfKinematics urdf(xml, source);
    const YAML::Node arm = need(root, "arm", w), head = need(root, "head", w);
    const YAML::Node stereo = need(head, "stereo_camera", w + ": head");
    const YAML::Node marker = need(arm, "marker", w + ": arm");
    auto link = [&](const YAML::Node& node, const char* key, const std::string& where) {
      return need(node, key, where).as<std::string>();
    };
    UrdfLinks links;
    links.base = root["base_frame"] ? root["base_frame"].as<std::string>() : urdf.rootLink();
    links.arm_tip = link(arm, "tip_link", w + ": arm");
    links.tool = link(arm, "tool_link", w + ": arm");
    links.marker = link(marker, "link", w + ": arm.marker");
    links.hand_camera = link(arm, "hand_camera_link", w + ": arm");
    links.ft_sensor = link(arm, "ft_sensor_link", w + ": arm");
    links.head_tip = link(head, "tip_link", w + ": head");
    links.left_camera = link(stereo, "left_link", w + ": head.stereo_camera");
    links.right_camera = link(stereo, "right_link", w + ": head.stereo_camera");
    // Optional: a mono camera on the head ({link, camera_info}).
    const YAML::Node mono = head["mono_camera"];
    if (mono) links.mono_camera = link(mono, "link", w + ": head.mono_camera");
    d.arm.link_prefix = arm["link_prefix"] ? arm["link_prefix"].as<std::string>() : "arm_link_";
    d.head.link_prefix = head["link_prefix"] ? head["link_prefix"].as<std::string>() : "head_link_";
    d = withUrdfKinematics(d, urdf, links);
    // A pan-tilt head, or cameras on a stand (no joint between base_frame and tip_link: eye-to-hand).
    if (d.head.joints.size() != 2 && !d.head.joints.empty()) {
      throw error(w + ": head.tip_link", "a head has 2 joints (pan, tilt) or none (a camera on a stand), not " +
                                             std::to_string(d.head.joints.size()));
    }
    d.marker_size = number(marker, "size", w + ": arm.marker");
    if (!(d.marker_size > 0)) throw error(w + ": arm.marker.size", "must be positive");
    const std::string ws = w + ": head.stereo_camera";
    d.image_width = static_cast<int>(numberOr(stereo, "width", 1024, ws));
    d.image_height = static_cast<int>(numberOr(stereo, "height", 768, ws));
    d.left_camera_info = fileNamedBy(stereo, "left_camera_info", path);
    d.right_camera_info = fileNamedBy(stereo, "right_camera_info", path);
    if (mono) d.mono_camera_info = fileNamedBy(mono, "camera_info", path);
    d.arm_calibration_pose = poseDeg(arm, "calibration_pose_deg", w + ": arm", d.arm);
    d.arm_home = poseDeg(arm, "home_deg", w + ": arm", d.arm);
    readHeadPosesAndSettings(root, w, d);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(w + ": " + e.what());
  }
  return d;
}

}  // namespace

RobotDescription withCalibrationCamera(RobotDescription d, const std::string& camera, const std::string& where) {
  if (camera != "stereo" && camera != "mono") {
    throw std::runtime_error(where + ": '" + camera + "' is no calibration camera (expected 'stereo' or 'mono')");
  }
  if (camera == "mono" && d.mono_camera.frame.empty()) {
    throw std::runtime_error(where + ": 'mono', but " + d.source + " gives the head no mono camera (head.mono_camera)");
  }
  d.calibration_camera = camera;
  return d;
}

ChainJoint fromDh(const DhJoint& j) {
  ChainJoint c;
  c.name = j.name;
  c.prismatic = j.prismatic;
  c.offset = j.prismatic ? j.d : j.theta_offset;
  c.origin = Eigen::Isometry3d(Eigen::AngleAxisd(j.prismatic ? j.theta_offset : 0.0, Eigen::Vector3d::UnitZ()));
  c.tip = Eigen::Isometry3d::Identity();
  c.tip.translate(Eigen::Vector3d(j.a, 0, j.prismatic ? 0.0 : j.d));  // Tz(d) Tx(a) commute
  c.tip.rotate(Eigen::AngleAxisd(j.alpha, Eigen::Vector3d::UnitX()));
  c.min = j.min;
  c.max = j.max;
  c.max_velocity = j.max_velocity;
  return c;
}

Eigen::Isometry3d dhTransform(const DhJoint& j, double q) { return Eigen::Isometry3d(jointMatrix(fromDh(j), q)); }

std::vector<ChainJoint> parseDhTable(const std::vector<double>& flat) {
  if (flat.empty() || flat.size() % 4 != 0) {
    throw std::invalid_argument("a DH table needs 4 values per joint (d, theta, a, alpha), got " +
                                std::to_string(flat.size()));
  }
  std::vector<ChainJoint> joints;
  for (size_t i = 0; i < flat.size(); i += 4) {
    for (size_t k = i; k < i + 4; ++k) {
      if (!std::isfinite(flat[k])) {
        throw std::invalid_argument("DH table row " + std::to_string(i / 4 + 1) + " has a value that is not finite");
      }
    }
    DhJoint j;
    j.name = "joint_" + std::to_string(i / 4 + 1);
    j.d = flat[i];
    j.theta_offset = flat[i + 1];
    j.a = flat[i + 2];
    j.alpha = flat[i + 3];
    j.min = -M_PI;
    j.max = M_PI;
    joints.push_back(fromDh(j));
  }
  return joints;
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

std::vector<std::string> KinematicChain::names() const {
  std::vector<std::string> n;
  for (const auto& j : joints) n.push_back(j.name);
  return n;
}

std::vector<Eigen::Isometry3d> KinematicChain::linkFrames(const std::vector<double>& q) const {
  if (q.size() != joints.size()) {
    throw std::invalid_argument("forward kinematics of '" + link_prefix + "*': expected " +
                                std::to_string(joints.size()) + " joint angles, got " + std::to_string(q.size()));
  }
  for (size_t i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q[i])) {
      throw std::invalid_argument("forward kinematics of '" + link_prefix + "*': joint '" + joints[i].name +
                                  "' position is not finite");
    }
  }
  std::vector<Eigen::Isometry3d> frames{mount};
  for (size_t i = 0; i < joints.size(); ++i) frames.push_back(frames.back() * Eigen::Isometry3d(jointMatrix(joints[i], q[i])));
  return frames;
}

std::string KinematicChain::limitViolation(const std::vector<double>& q) const {
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
  if (urdfForm(root)) return fromUrdf(root, path);
  RobotDescription d;
  d.source = path;
  try {
    if (root["name"]) d.name = root["name"].as<std::string>();
    if (root["base_frame"]) d.base_frame = root["base_frame"].as<std::string>();
    const YAML::Node arm = need(root, "arm", w);
    d.arm = chain(arm, w + ": arm");
    d.tool = fixedFrame(need(arm, "tool", w + ": arm"), w + ": arm.tool", "tcp");
    const YAML::Node marker = need(arm, "marker", w + ": arm");
    d.marker = fixedFrame(marker, w + ": arm.marker", "gripper_marker");
    d.marker_size = number(marker, "size", w + ": arm.marker");
    if (!(d.marker_size > 0)) throw error(w + ": arm.marker.size", "must be positive");
    d.hand_camera = fixedFrame(need(arm, "hand_camera", w + ": arm"), w + ": arm.hand_camera", "hand_camera_optical_frame");
    d.ft_sensor = fixedFrame(need(arm, "ft_sensor", w + ": arm"), w + ": arm.ft_sensor", "ft_sensor");
    d.arm_calibration_pose = poseDeg(arm, "calibration_pose_deg", w + ": arm", d.arm);
    d.arm_home = poseDeg(arm, "home_deg", w + ": arm", d.arm);

    const YAML::Node head = need(root, "head", w);
    d.head = chain(head, w + ": head");
    if (d.head.joints.size() != 2) throw error(w + ": head.joints", "a pan-tilt head has exactly 2 joints");
    const YAML::Node stereo = need(head, "stereo_camera", w + ": head");
    const std::string ws = w + ": head.stereo_camera";
    d.left_camera = fixedFrame(need(stereo, "left", ws), ws + ".left", "");
    d.left_camera.frame = stereo["left_frame"] ? stereo["left_frame"].as<std::string>() : "stereo_left_optical_frame";
    if (stereo["right_frame"]) d.right_camera_frame = stereo["right_frame"].as<std::string>();
    d.stereo_baseline = number(stereo, "baseline", ws);
    d.image_width = static_cast<int>(numberOr(stereo, "width", 1024, ws));
    d.image_height = static_cast<int>(numberOr(stereo, "height", 768, ws));
    d.left_camera_info = fileNamedBy(stereo, "left_camera_info", path);
    d.right_camera_info = fileNamedBy(stereo, "right_camera_info", path);
    readHeadPosesAndSettings(root, w, d);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(w + ": " + e.what());
  }
  return d;
}

namespace {

// The names free_params may hold, and what each sets.
std::vector<std::pair<std::string, std::function<void(FreeParams&)>>> freeParamNames(const RobotDescription& d) {
  std::vector<std::pair<std::string, std::function<void(FreeParams&)>>> names;
  names.emplace_back("fixed_point", [](FreeParams& f) { f.fixed_point = true; });
  names.emplace_back("target_offset", [](FreeParams& f) { f.target_offset = true; });
  std::vector<std::pair<bool, size_t>> joints;  // (arm, index) of the estimable offsets
  for (size_t j = 1; j + 1 < d.arm.joints.size(); ++j) joints.push_back({true, j});
  for (size_t j = 1; j < d.head.joints.size(); ++j) joints.push_back({false, j});
  names.emplace_back("joint_offsets", [joints](FreeParams& f) {
    for (const auto& [arm, j] : joints) (arm ? f.arm : f.head).push_back(j);
  });
  for (const auto& [arm, j] : joints) {
    names.emplace_back((arm ? d.arm : d.head).joints[j].name, [arm = arm, j = j](FreeParams& f) { (arm ? f.arm : f.head).push_back(j); });
  }
  return names;
}

}  // namespace

FreeParams freeParams(const RobotDescription& d) {
  const auto names = freeParamNames(d);
  FreeParams f;
  if (d.free_params.empty()) {
    for (const auto& n : names) n.second(f);
  } else {
    f.fixed_point = f.target_offset = false;
  }
  for (const std::string& p : d.free_params) {
    auto it = std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.first == p; });
    if (it == names.end()) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n.first;
      throw error(d.source + ": free_params", "unknown parameter '" + p + "' (known: " + known + ")");
    }
    it->second(f);
  }
  for (auto* v : {&f.arm, &f.head}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return f;
}

void useUrdfFile(const std::string& path) { urdfFileForAll() = path; }

std::string ownUrdf(const RobotDescription& d, std::string& source) {
  const YAML::Node root = descriptionYaml(d);
  if (!root || !urdfForm(root)) return "";
  return urdfText(root, d.source, source);
}

std::string urdfFileOf(const RobotDescription& d) {
  const YAML::Node root = descriptionYaml(d);
  return root ? fileNamedBy(root, "urdf", d.source) : "";
}

std::string exampleRobotDescriptionPath() {
  const std::string pkg = ros::package::getPath("robot_description");
  if (pkg.empty()) throw std::runtime_error("package robot_description not found (ROS_PACKAGE_PATH)");
  return pkg + "/config/example/robot.yaml";
}

Eigen::Isometry3d RobotModel::tcp(const std::vector<double>& q) const { return d_.arm.end(q) * d_.tool.pose; }
Eigen::Isometry3d RobotModel::marker(const std::vector<double>& q) const { return tcp(q) * d_.marker.pose; }
Eigen::Isometry3d RobotModel::handCamera(const std::vector<double>& q) const { return tcp(q) * d_.hand_camera.pose; }
Eigen::Isometry3d RobotModel::ftSensor(const std::vector<double>& q) const { return d_.arm.end(q) * d_.ft_sensor.pose; }
Eigen::Isometry3d RobotModel::leftCamera(const std::vector<double>& q) const {
  return d_.head.end(q) * d_.left_camera.pose;
}
Eigen::Isometry3d RobotModel::monoCamera(const std::vector<double>& q) const {
  return d_.head.end(q) * d_.mono_camera.pose;
}

Eigen::Isometry3d RobotModel::calibrationCamera(const std::vector<double>& q) const {
  return d_.calibration_camera == "mono" ? monoCamera(q) : leftCamera(q);
}
Eigen::Isometry3d RobotModel::leftToRight() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(d_.stereo_baseline, 0, 0);
  return t;
}
Eigen::Isometry3d RobotModel::rightCamera(const std::vector<double>& q) const { return leftCamera(q) * leftToRight(); }

std::array<double, 2> RobotModel::lookAt(const Eigen::Vector3d& target, std::array<double, 2> start) const {
  if (d_.head.joints.size() != 2) throw std::logic_error(d_.source + ": only a pan-tilt head can look at a point");
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

}  // namespace robot_description
