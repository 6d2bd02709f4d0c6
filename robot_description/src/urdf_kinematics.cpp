#include "robot_description/urdf_kinematics.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <console_bridge/console.h>
#include <kdl/chain.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <urdf/model.h>

namespace robot_description {
namespace {

Eigen::Isometry3d toEigen(const KDL::Frame& f) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    t.translation()[r] = f.p(r);
    for (int c = 0; c < 3; ++c) t.linear()(r, c) = f.M(r, c);
  }
  return t;
}

Eigen::Vector3d toEigen(const KDL::Vector& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

// What the urdf parser says while it parses (through console_bridge, where it writes its reasons):
// kept for the error instead of printed apart from it. One parse at a time: the handler is global.
class ParserMessages : public console_bridge::OutputHandler {
 public:
  ParserMessages() : lock_(mutex()) { console_bridge::useOutputHandler(this); }
  ~ParserMessages() override { console_bridge::restorePreviousOutputHandler(); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) text_ += (text_.empty() ? "" : "; ") + text;
  }
  const std::string& text() const { return text_; }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  std::string text_;
};

bool isPrismatic(KDL::Joint::JointType t) {
  return t == KDL::Joint::TransAxis || t == KDL::Joint::TransX || t == KDL::Joint::TransY || t == KDL::Joint::TransZ;
}

}  // namespace

struct UrdfKinematics::Data {
  std::string source;
  urdf::Model model;
  KDL::Tree tree;

  KDL::Chain kdlChain(const std::string& root, const std::string& tip) const {
    for (const auto& link : {root, tip}) {
      if (!model.getLink(link)) throw std::runtime_error(source + ": the URDF has no link '" + link + "'");
    }
    KDL::Chain c;
    if (!tree.getChain(root, tip, c)) {
      throw std::runtime_error(source + ": no chain from link '" + root + "' to link '" + tip + "'");
    }
    return c;
  }
};

UrdfKinematics::UrdfKinematics(const std::string& urdf_xml, const std::string& source) : data_(std::make_unique<Data>()) {
  data_->source = source;
  std::string why;
  bool parsed = false;
  {
    ParserMessages messages;
    parsed = data_->model.initString(urdf_xml);
    why = messages.text();
  }
  if (!parsed) throw std::runtime_error(source + ": not a valid URDF: " + (why.empty() ? "the urdf parser refused it" : why));
  if (!kdl_parser::treeFromUrdfModel(data_->model, data_->tree)) {
    throw std::runtime_error(source + ": KDL cannot build a kinematic tree from this URDF");
  }
}

UrdfKinematics UrdfKinematics::fromFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("URDF '" + path + "': cannot read the file");
  std::ostringstream text;
  text << f.rdbuf();
  return UrdfKinematics(text.str(), "URDF '" + path + "'");
}

UrdfKinematics::UrdfKinematics(UrdfKinematics&&) noexcept = default;
UrdfKinematics::~UrdfKinematics() = default;
const std::string& UrdfKinematics::source() const { return data_->source; }
std::string UrdfKinematics::rootLink() const { return data_->model.getRoot()->name; }

KinematicChain UrdfKinematics::chain(const std::string& root, const std::string& tip) const {
  const KDL::Chain kc = data_->kdlChain(root, tip);
  KinematicChain out;
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();  // fixed joints since the last moving one
  auto flush = [&] {
    if (out.joints.empty()) out.mount = out.mount * pending;
    else out.joints.back().tip = out.joints.back().tip * pending;
    pending.setIdentity();
  };
  for (const KDL::Segment& s : kc.segments) {
    const KDL::Joint& j = s.getJoint();
    if (j.getType() == KDL::Joint::None) {
      pending = pending * toEigen(s.pose(0.0));
      continue;
    }
    flush();
    // KDL moves a segment by its joint: a rotation about the line through JointOrigin along
    // JointAxis (a translation along JointAxis) in the segment's parent frame, then the frame to
    // its tip: pose(q) = Trans(o) Rot(a, q) Trans(-o) pose(0).
    ChainJoint c;
    c.name = j.getName();
    c.prismatic = isPrismatic(j.getType());
    c.axis = toEigen(j.JointAxis()).normalized();
    const Eigen::Vector3d o = c.prismatic ? Eigen::Vector3d::Zero() : toEigen(j.JointOrigin());
    c.origin = Eigen::Translation3d(o) * Eigen::Isometry3d::Identity();
    c.tip = Eigen::Translation3d(-o) * toEigen(s.pose(0.0));
    // KDL's own pose at another position must agree (a joint with a scale or an offset would not).
    const Eigen::Isometry3d kdl = toEigen(s.pose(0.7)), ours(jointMatrix(c, 0.7));
    if (!kdl.isApprox(ours, 1e-9)) {
      throw std::runtime_error(data_->source + ": joint '" + c.name + "' moves differently from a plain " +
                               (c.prismatic ? "prismatic" : "revolute") + " joint (scaled or offset?)");
    }
    const auto uj = data_->model.getJoint(c.name);
    if (uj && uj->type != urdf::Joint::CONTINUOUS && uj->limits) {
      c.min = uj->limits->lower;
      c.max = uj->limits->upper;
    } else {
      c.min = -std::numeric_limits<double>::infinity();
      c.max = std::numeric_limits<double>::infinity();
    }
    c.max_velocity = uj && uj->limits && uj->limits->velocity > 0 ? uj->limits->velocity
                                                                    : std::numeric_limits<double>::infinity();
    out.joints.push_back(c);
  }
  flush();
  out.tip_link = tip;
  return out;
}

Eigen::Isometry3d UrdfKinematics::fixedTransform(const std::string& root, const std::string& tip) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (const KDL::Segment& s : data_->kdlChain(root, tip).segments) {
    if (s.getJoint().getType() != KDL::Joint::None) {
      throw std::runtime_error(data_->source + ": link '" + tip + "' is not fixed to link '" + root + "': joint '" +
                               s.getJoint().getName() + "' moves between them");
    }
    t = t * toEigen(s.pose(0.0));
  }
  return t;
}

RobotDescription withUrdfKinematics(RobotDescription d, const UrdfKinematics& urdf, const UrdfLinks& links) {
  d.base_frame = links.base;
  auto chain = [&](KinematicChain& c, const std::string& tip) {
    const std::string prefix = c.link_prefix;
    c = urdf.chain(links.base, tip);
    c.link_prefix = prefix;
  };
  chain(d.arm, links.arm_tip);
  if (d.arm.joints.empty()) {
    throw std::runtime_error(urdf.source() + ": the arm chain from link '" + links.base + "' to link '" + links.arm_tip +
                             "' has no moving joint");
  }
  chain(d.head, links.head_tip);
  auto fixed = [&](FixedFrame& f, const std::string& parent, const std::string& link) {
    f.frame = link;
    f.pose = urdf.fixedTransform(parent, link);
  };
  fixed(d.tool, links.arm_tip, links.tool);
  fixed(d.marker, links.tool, links.marker);
  fixed(d.hand_camera, links.tool, links.hand_camera);
  fixed(d.ft_sensor, links.arm_tip, links.ft_sensor);
  fixed(d.left_camera, links.head_tip, links.left_camera);
  if (!links.mono_camera.empty()) fixed(d.mono_camera, links.head_tip, links.mono_camera);
  const Eigen::Isometry3d right = urdf.fixedTransform(links.left_camera, links.right_camera);
  const double angle = Eigen::AngleAxisd(right.linear()).angle();
  if (angle > 1e-9 || std::abs(right.translation().y()) > 1e-9 || std::abs(right.translation().z()) > 1e-9) {
    throw std::runtime_error(urdf.source() + ": link '" + links.right_camera + "' must be link '" + links.left_camera +
                             "' moved along its x axis (a rectified stereo pair)");
  }
  d.right_camera_frame = links.right_camera;
  d.stereo_baseline = right.translation().x();
  return d;
}

UrdfLinks generatedUrdfLinks(const RobotDescription& d) {
  UrdfLinks l;
  l.base = d.base_frame;
  l.arm_tip = d.arm.link_prefix + std::to_string(d.arm.joints.size());
  l.tool = d.tool.frame;
  l.marker = d.marker.frame;
  l.hand_camera = d.hand_camera.frame;
  l.ft_sensor = d.ft_sensor.frame;
  l.head_tip = d.head.link_prefix + std::to_string(d.head.joints.size());
  l.left_camera = d.left_camera.frame;
  l.right_camera = d.right_camera_frame;
  return l;
}

}  // namespace robot_description
