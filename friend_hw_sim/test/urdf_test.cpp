// The generated URDF and the DH forward kinematics must agree: compose the URDF's joint
// transforms (as robot_state_publisher does) and compare every frame with RobotModel.
#include <map>
#include <random>

#include <gtest/gtest.h>
#include <urdf/model.h>

#include "robot_description/robot_model.h"
#include "friend_hw_sim/true_robot.h"
#include "robot_description/urdf_generator.h"
#include "imagenets/package_file.h"

using namespace friend_hw_sim;
using namespace robot_description;

namespace {

Eigen::Isometry3d toEigen(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return t;
}

// Pose of `link` in the root, given joint positions by name.
Eigen::Isometry3d linkPose(const urdf::Model& model, const std::string& link, const std::map<std::string, double>& q) {
  auto l = model.getLink(link);
  if (!l) throw std::runtime_error("URDF has no link '" + link + "'");
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  while (l->parent_joint) {
    const auto& j = *l->parent_joint;
    Eigen::Isometry3d jt = toEigen(j.parent_to_joint_origin_transform);
    if (j.type == urdf::Joint::REVOLUTE) {
      const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
      jt.rotate(Eigen::AngleAxisd(q.at(j.name), axis));
    }
    t = jt * t;
    l = l->getParent();
  }
  return t;
}

void expectSame(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const std::string& what) {
  EXPECT_LT((a.translation() - b.translation()).norm(), 1e-6) << what;
  EXPECT_LT(Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle(), 1e-6) << what;
}

void checkAgreement(const RobotDescription& d) {
  urdf::Model model;
  ASSERT_TRUE(model.initString(generateUrdf(d))) << "generated URDF does not parse";
  EXPECT_EQ(model.getRoot()->name, d.base_frame);
  const RobotModel fk(d);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> arm, head;
    std::map<std::string, double> q;
    for (const auto& j : d.arm.joints) arm.push_back(q[j.name] = std::uniform_real_distribution<double>(j.min, j.max)(rng));
    for (const auto& j : d.head.joints) head.push_back(q[j.name] = std::uniform_real_distribution<double>(j.min, j.max)(rng));
    const auto arm_frames = d.arm.linkFrames(arm), head_frames = d.head.linkFrames(head);
    for (size_t i = 0; i < arm_frames.size(); ++i) {
      const std::string name = d.arm.link_prefix + std::to_string(i);
      expectSame(linkPose(model, name, q), arm_frames[i], name);
    }
    for (size_t i = 0; i < head_frames.size(); ++i) {
      const std::string name = d.head.link_prefix + std::to_string(i);
      expectSame(linkPose(model, name, q), head_frames[i], name);
    }
    expectSame(linkPose(model, d.tool.frame, q), fk.tcp(arm), "tcp");
    expectSame(linkPose(model, d.marker.frame, q), fk.marker(arm), "marker");
    expectSame(linkPose(model, d.hand_camera.frame, q), fk.handCamera(arm), "hand camera");
    expectSame(linkPose(model, d.ft_sensor.frame, q), fk.ftSensor(arm), "ft sensor");
    expectSame(linkPose(model, d.left_camera.frame, q), fk.leftCamera(head), "left camera");
    expectSame(linkPose(model, d.right_camera_frame, q), fk.rightCamera(head), "right camera");
  }
}

}  // namespace

TEST(Urdf, NominalRobotAgreesWithDhKinematics) { checkAgreement(loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"))); }

TEST(Urdf, TrueRobotAgreesWithItsDhKinematics) {
  const auto nominal = loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"));
  checkAgreement(applyTrueError(nominal, loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), nominal)));
  checkAgreement(applyTrueError(nominal, loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), nominal, 42)));
}
