#include "robot_description/urdf_writer.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <tinyxml2.h>

#include "robot_description/urdf_generator.h"
#include "robot_description/urdf_kinematics.h"

namespace robot_description {
namespace {

using tinyxml2::XMLElement;

// A robot's own URDF as an XML document, with the look-ups the changes need.
class UrdfDocument {
 public:
  // `xml` read from `path` (a file or a parameter, for messages).
  UrdfDocument(const std::string& xml, const std::string& path) : path_(path) {
    if (doc_.Parse(xml.c_str()) != tinyxml2::XML_SUCCESS) {
      throw std::runtime_error("URDF '" + path + "': cannot read it as XML: " + doc_.ErrorStr());
    }
    robot_ = doc_.FirstChildElement("robot");
    if (!robot_) throw std::runtime_error("URDF '" + path + "': no <robot> element");
  }

  XMLElement* joint(const std::string& name) {
    for (XMLElement* j = robot_->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      if (attribute(j, "name") == name) return j;
    }
    throw std::runtime_error("URDF '" + path_ + "': no joint '" + name + "'");
  }
  // The joint whose child is `link` (null if none: the root).
  XMLElement* jointTo(const std::string& link) {
    for (XMLElement* j = robot_->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      if (linkOf(j, "child") == link) return j;
    }
    return nullptr;
  }
  XMLElement* fixedJointTo(const std::string& link, const std::string& what) {
    XMLElement* j = jointTo(link);
    if (!j || attribute(j, "type") != "fixed") {
      throw std::runtime_error("URDF '" + path_ + "': link '" + link + "' (" + what + ") hangs from " +
                               (j ? "joint '" + attribute(j, "name") + "', which is not fixed" : "no joint") +
                               ": a fixed joint must place it to hold a calibrated origin");
    }
    return j;
  }
  UrdfJoint describe(XMLElement* j) { return {attribute(j, "name"), linkOf(j, "parent"), linkOf(j, "child")}; }

  static std::string attribute(const XMLElement* e, const char* name) {
    const char* v = e ? e->Attribute(name) : nullptr;
    return v ? v : "";
  }
  static std::string linkOf(const XMLElement* joint, const char* which) {
    return attribute(joint->FirstChildElement(which), "link");
  }
  Eigen::Vector3d triple(const XMLElement* e, const char* name, const Eigen::Vector3d& otherwise) const {
    const std::string text = attribute(e, name);
    if (text.empty()) return otherwise;
    std::istringstream in(text);
    Eigen::Vector3d v;
    if (!(in >> v.x() >> v.y() >> v.z())) {
      throw std::runtime_error("URDF '" + path_ + "': attribute " + name + "=\"" + text + "\" is not three numbers");
    }
    return v;
  }
  Eigen::Isometry3d origin(const XMLElement* joint) const {
    const XMLElement* o = joint->FirstChildElement("origin");
    return fromXyzRpy(triple(o, "xyz", Eigen::Vector3d::Zero()), triple(o, "rpy", Eigen::Vector3d::Zero()));
  }
  Eigen::Vector3d axis(const XMLElement* joint) const {
    return triple(joint->FirstChildElement("axis"), "xyz", Eigen::Vector3d::UnitX()).normalized();
  }
  void setOrigin(XMLElement* joint, const Eigen::Isometry3d& t) {
    XMLElement* o = joint->FirstChildElement("origin");
    if (!o) {
      o = doc_.NewElement("origin");
      joint->InsertFirstChild(o);
    }
    const Eigen::Vector3d p = t.translation(), rpy = rpyOf(t.linear());
    char xyz[128], angles[128];
    std::snprintf(xyz, sizeof xyz, "%.17g %.17g %.17g", p.x(), p.y(), p.z());
    std::snprintf(angles, sizeof angles, "%.17g %.17g %.17g", rpy.x(), rpy.y(), rpy.z());
    o->SetAttribute("xyz", xyz);
    o->SetAttribute("rpy", angles);
  }
  void comment(const std::string& text) {
    tinyxml2::XMLNode* first = doc_.FirstChild();
    tinyxml2::XMLComment* c = doc_.NewComment(text.c_str());
    if (first && first->ToDeclaration()) doc_.InsertAfterChild(first, c);
    else doc_.InsertFirstChild(c);
  }
  std::string text() const {
    tinyxml2::XMLPrinter printer;
    doc_.Print(&printer);
    return printer.CStr();
  }

 private:
  std::string path_;
  tinyxml2::XMLDocument doc_;
  XMLElement* robot_ = nullptr;
};

bool same(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) { return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff() < 1e-15; }

std::string commentText(const std::string& note) {
  std::string text = "\n" + note + (note.empty() || note.back() == '\n' ? "" : "\n");
  for (size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) text.replace(at, 2, "- -");
  return text;
}

// The fixed joint that places a chain's link 0: the one to the link its first moving joint hangs
// from; for a chain of fixed joints only (a camera on a stand), the one to its tip link.
XMLElement* mountJoint(UrdfDocument& urdf, const KinematicChain& chain) {
  if (chain.joints.empty()) {
    if (chain.tip_link.empty()) throw std::runtime_error("a chain without joints and without a tip link has no mount joint");
    return urdf.fixedJointTo(chain.tip_link, "the tip link of a chain without joints");
  }
  return urdf.fixedJointTo(UrdfDocument::linkOf(urdf.joint(chain.joints.front().name), "parent"),
                           "the link joint '" + chain.joints.front().name + "' hangs from");
}

}  // namespace

UrdfJoint urdfChainMountJoint(const RobotDescription& d, const KinematicChain& chain) {
  std::string file;
  const std::string xml = ownUrdf(d, file);
  if (xml.empty()) return {chain.link_prefix + "0_mount", d.base_frame, chain.link_prefix + "0"};
  UrdfDocument urdf(xml, file);
  return urdf.describe(mountJoint(urdf, chain));
}

UrdfJoint urdfFixedJoint(const RobotDescription& d, const std::string& link) {
  std::string file;
  const std::string xml = ownUrdf(d, file);
  if (xml.empty()) return {link + "_joint", "", link};
  UrdfDocument urdf(xml, file);
  return urdf.describe(urdf.fixedJointTo(link, "a fixed frame"));
}

std::string writeUrdf(const RobotDescription& nominal, const RobotDescription& changed, const std::string& robot_name,
                      const std::string& note) {
  std::string file;
  const std::string xml = ownUrdf(nominal, file);
  if (xml.empty()) return generateUrdf(changed, robot_name, note);
  UrdfDocument urdf(xml, file);
  for (const auto& [n, c] : {std::make_pair(&nominal.arm, &changed.arm), std::make_pair(&nominal.head, &changed.head)}) {
    if (n->joints.size() != c->joints.size()) {
      throw std::runtime_error(file + ": the changed description's chain has " + std::to_string(c->joints.size()) +
                               " joints, the URDF's " + std::to_string(n->joints.size()));
    }
    if (!same(n->mount, c->mount)) {
      XMLElement* j = mountJoint(urdf, *n);
      urdf.setOrigin(j, urdf.origin(j) * n->mount.inverse() * c->mount);
    }
    for (size_t i = 0; i < n->joints.size(); ++i) {
      const double delta = c->joints[i].offset - n->joints[i].offset;
      if (delta == 0.0) continue;
      // URDF joint: origin * Motion(axis, q). The zero offset moves the joint by `delta` first.
      XMLElement* j = urdf.joint(n->joints[i].name);
      const Eigen::Vector3d axis = urdf.axis(j);
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      if (n->joints[i].prismatic) motion.translation() = axis * delta;
      else motion.linear() = Eigen::AngleAxisd(delta, axis).toRotationMatrix();
      urdf.setOrigin(j, urdf.origin(j) * motion);
    }
  }
  for (const auto& [n, c] : {std::make_pair(&nominal.tool, &changed.tool), std::make_pair(&nominal.marker, &changed.marker),
                             std::make_pair(&nominal.hand_camera, &changed.hand_camera),
                             std::make_pair(&nominal.ft_sensor, &changed.ft_sensor),
                             std::make_pair(&nominal.left_camera, &changed.left_camera)}) {
    if (same(n->pose, c->pose)) continue;
    // The joint's parent stays where it was: only its own origin takes up the change.
    XMLElement* j = urdf.fixedJointTo(n->frame, "a fixed frame");
    urdf.setOrigin(j, urdf.origin(j) * n->pose.inverse() * c->pose);
  }
  urdf.comment(commentText("Written from " + file + " by robot_description::writeUrdf" +
                           (note.empty() ? std::string(".") : ":\n" + note)));
  return urdf.text();
}

}  // namespace robot_description
