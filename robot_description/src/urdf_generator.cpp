#include "robot_description/urdf_generator.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace robot_description {
namespace {

class UrdfWriter {
 public:
  UrdfWriter() { out_ << std::setprecision(17); }

  void origin(const Eigen::Isometry3d& t) {
    const Eigen::Vector3d p = t.translation(), rpy = rpyOf(t.linear());
    out_ << "    <origin xyz=\"" << p.x() << " " << p.y() << " " << p.z() << "\" rpy=\"" << rpy.x() << " " << rpy.y()
         << " " << rpy.z() << "\"/>\n";
  }

  struct Shape {
    std::string geometry;  // e.g. <cylinder radius=".." length=".."/>
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    std::string material;
  };

  void link(const std::string& name, const std::vector<Shape>& shapes = {}) {
    out_ << "  <link name=\"" << name << "\">\n";
    for (const auto& s : shapes) {
      out_ << "   <visual>\n  ";
      origin(s.pose);
      out_ << "    <geometry>" << s.geometry << "</geometry>\n";
      out_ << "    <material name=\"" << s.material << "\"/>\n   </visual>\n";
    }
    out_ << "  </link>\n";
  }

  void joint(const std::string& name, const std::string& type, const std::string& parent, const std::string& child,
             const Eigen::Isometry3d& pose, const ChainJoint* limits = nullptr) {
    out_ << "  <joint name=\"" << name << "\" type=\"" << type << "\">\n";
    out_ << "    <parent link=\"" << parent << "\"/>\n    <child link=\"" << child << "\"/>\n";
    origin(pose);
    if (limits) {
      out_ << "    <axis xyz=\"" << limits->axis.x() << " " << limits->axis.y() << " " << limits->axis.z() << "\"/>\n";
      out_ << "    <limit lower=\"" << limits->min << "\" upper=\"" << limits->max << "\" effort=\"100\" velocity=\""
           << limits->max_velocity << "\"/>\n";
    }
    out_ << "  </joint>\n";
  }

  std::ostringstream& raw() { return out_; }

 private:
  std::ostringstream out_;
};

// A cylinder from the origin to `to` (in the link frame).
UrdfWriter::Shape rod(const Eigen::Vector3d& to, double radius, const std::string& material) {
  UrdfWriter::Shape s;
  std::ostringstream g;
  g << std::setprecision(9) << "<cylinder radius=\"" << radius << "\" length=\"" << to.norm() << "\"/>";
  s.geometry = g.str();
  s.pose.translation() = to / 2;
  s.pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), to).toRotationMatrix();
  s.material = material;
  return s;
}

UrdfWriter::Shape box(const Eigen::Vector3d& size, const Eigen::Vector3d& centre, const std::string& material) {
  UrdfWriter::Shape s;
  std::ostringstream g;
  g << std::setprecision(9) << "<box size=\"" << size.x() << " " << size.y() << " " << size.z() << "\"/>";
  s.geometry = g.str();
  s.pose.translation() = centre;
  s.material = material;
  return s;
}

UrdfWriter::Shape cylinder(double radius, double length, const std::string& material) {
  UrdfWriter::Shape s;
  std::ostringstream g;
  g << std::setprecision(9) << "<cylinder radius=\"" << radius << "\" length=\"" << length << "\"/>";
  s.geometry = g.str();
  s.material = material;
  return s;
}

void writeChain(UrdfWriter& w, const std::string& base, const KinematicChain& c, double radius, const std::string& material) {
  const std::string link0 = c.link_prefix + "0";
  w.link(link0);
  w.joint(link0 + "_mount", "fixed", base, link0, c.mount);
  for (size_t i = 0; i < c.joints.size(); ++i) {
    const ChainJoint& j = c.joints[i];
    const std::string parent = c.link_prefix + std::to_string(i), child = c.link_prefix + std::to_string(i + 1);
    const std::string rotor = j.name + "_rotor";
    // The rotor frame moves with the joint; the next link's origin sits at the tip's constant translation.
    std::vector<UrdfWriter::Shape> shapes{cylinder(radius * 1.25, radius * 2.5, "joint_grey")};
    const Eigen::Vector3d next = j.tip.translation();
    if (next.norm() > 1e-6) shapes.push_back(rod(next, radius, material));
    w.link(rotor, shapes);
    // The joint's zero offset is part of its origin: URDF consumers (robot_state_publisher, KDL)
    // apply no offsets of their own.
    Eigen::Isometry3d origin = j.origin;
    if (j.prismatic) origin.translate(j.axis * j.offset);
    else origin.rotate(Eigen::AngleAxisd(j.offset, j.axis));
    w.joint(j.name, j.prismatic ? "prismatic" : "revolute", parent, rotor, origin, &j);
    w.link(child);
    w.joint(child + "_dh", "fixed", rotor, child, j.tip);
  }
}

}  // namespace

std::string generateUrdf(const RobotDescription& d, const std::string& robot_name, const std::string& note) {
  UrdfWriter w;
  auto& o = w.raw();
  o << "<?xml version=\"1.0\"?>\n";
  o << "<!-- Generated from " << d.source << " (classic DH) by robot_description::generateUrdf. Do not edit. -->\n";
  if (!note.empty()) {
    std::string text = note;
    for (size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) text.replace(at, 2, "- -");
    o << "<!--\n" << text << (text.back() == '\n' ? "" : "\n") << "-->\n";
  }
  o << "<robot name=\"" << (robot_name.empty() ? d.name : robot_name) << "\">\n";
  o << "  <material name=\"chair_blue\"><color rgba=\"0.2 0.3 0.6 1\"/></material>\n";
  o << "  <material name=\"arm_silver\"><color rgba=\"0.75 0.75 0.8 1\"/></material>\n";
  o << "  <material name=\"joint_grey\"><color rgba=\"0.35 0.35 0.4 1\"/></material>\n";
  o << "  <material name=\"head_black\"><color rgba=\"0.1 0.1 0.1 1\"/></material>\n";
  o << "  <material name=\"marker_white\"><color rgba=\"0.95 0.95 0.95 1\"/></material>\n";
  o << "  <material name=\"ft_orange\"><color rgba=\"0.9 0.5 0.1 1\"/></material>\n";

  // The wheelchair (a box under the seat) and the mast carrying the head.
  const Eigen::Vector3d mast_foot(d.head.mount.translation().x(), d.head.mount.translation().y(), 0.45);
  auto mast = rod(d.head.mount.translation() - mast_foot, 0.02, "joint_grey");
  mast.pose.translation() += mast_foot;
  w.link(d.base_frame, {box({0.7, 0.6, 0.45}, {0.1, 0, 0.225}, "chair_blue"), mast});

  writeChain(w, d.base_frame, d.arm, 0.04, "arm_silver");
  writeChain(w, d.base_frame, d.head, 0.02, "joint_grey");

  const std::string arm_end = d.arm.link_prefix + std::to_string(d.arm.joints.size());
  const std::string head_end = d.head.link_prefix + std::to_string(d.head.joints.size());
  // Gripper: two fingers around the TCP, the marker plate on the gripper.
  {
    auto finger_a = box({0.015, 0.02, 0.08}, {0.03, 0, -0.04}, "joint_grey");
    auto finger_b = box({0.015, 0.02, 0.08}, {-0.03, 0, -0.04}, "joint_grey");
    w.link(d.tool.frame, {finger_a, finger_b});
    w.joint(d.tool.frame + "_joint", "fixed", arm_end, d.tool.frame, d.tool.pose);
    w.link(d.marker.frame, {box({d.marker_size, d.marker_size, 0.002}, {0, 0, -0.001}, "marker_white")});
    w.joint(d.marker.frame + "_joint", "fixed", d.tool.frame, d.marker.frame, d.marker.pose);
    w.link(d.hand_camera.frame, {box({0.03, 0.03, 0.03}, {0, 0, -0.015}, "head_black")});
    w.joint(d.hand_camera.frame + "_joint", "fixed", d.tool.frame, d.hand_camera.frame, d.hand_camera.pose);
    auto ft = cylinder(0.045, 0.03, "ft_orange");
    w.link(d.ft_sensor.frame, {ft});
    w.joint(d.ft_sensor.frame + "_joint", "fixed", arm_end, d.ft_sensor.frame, d.ft_sensor.pose);
  }
  // Stereo camera: a bar between the two lenses, on the left optical frame (x right, z forward).
  {
    auto bar = box({d.stereo_baseline + 0.06, 0.04, 0.04}, {d.stereo_baseline / 2, 0, -0.02}, "head_black");
    w.link(d.left_camera.frame, {bar, cylinder(0.015, 0.02, "joint_grey")});
    w.joint(d.left_camera.frame + "_joint", "fixed", head_end, d.left_camera.frame, d.left_camera.pose);
    Eigen::Isometry3d right = Eigen::Isometry3d::Identity();
    right.translation().x() = d.stereo_baseline;
    w.link(d.right_camera_frame, {cylinder(0.015, 0.02, "joint_grey")});
    w.joint(d.right_camera_frame + "_joint", "fixed", d.left_camera.frame, d.right_camera_frame, right);
  }
  if (!d.mono_camera.frame.empty()) {
    w.link(d.mono_camera.frame, {cylinder(0.012, 0.02, "joint_grey")});
    w.joint(d.mono_camera.frame + "_joint", "fixed", head_end, d.mono_camera.frame, d.mono_camera.pose);
  }
  o << "</robot>\n";
  return o.str();
}

}  // namespace robot_description
