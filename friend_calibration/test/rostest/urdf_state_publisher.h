// Debian's robot_state_publisher started, as a user would, on a URDF file that a node wrote (the
// calibrated URDF), in its own namespace and on its own TF topics beside the simulator's; what it
// publishes is collected in a tf2 buffer. For the rostests of the calibrated URDF.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2/buffer_core.h>
#include <tf2_msgs/TFMessage.h>

#include "imagenets/vision/frames.h"
#include "robot_description/robot_model.h"
#include "imagenets/testing/rostest_util.h"
#include "files_and_processes.h"

class UrdfStatePublisher {
 public:
  // robot_description = the file's text, under namespace `ns` ("/calibrated_urdf").
  UrdfStatePublisher(const std::string& ns, const std::string& urdf_file) {
    ros::param::set(ns + "/robot_description", readFile(urdf_file));
    tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>(ns + "/tf", 100, add(false));
    static_sub_ = nh_.subscribe<tf2_msgs::TFMessage>(ns + "/tf_static", 10, add(true));
    joints_ = nh_.advertise<sensor_msgs::JointState>(ns + "/joint_states", 10);
    process_ = std::make_unique<ChildProcess>(std::vector<std::string>{
        "rosrun", "robot_state_publisher", "robot_state_publisher", "__ns:=" + ns, "__name:=calibrated_state_publisher",
        "/tf:=" + ns + "/tf", "/tf_static:=" + ns + "/tf_static"});
  }
  bool started() const { return process_->started(); }
  bool canTransform(const std::string& base, const std::string& child) { return buffer_.canTransform(base, child, ros::Time(0)); }
  // Publishes the joint states (stamped now) until every frame can be looked up from `base`.
  bool waitForFrames(const std::string& base, const std::vector<std::string>& frames, sensor_msgs::JointState js,
                     double timeout) {
    return waitFor(
        [&] {
          js.header.stamp = ros::Time::now();
          joints_.publish(js);
          for (const auto& f : frames) {
            if (!canTransform(base, f)) return false;
          }
          return true;
        },
        timeout);
  }
  Eigen::Isometry3d lookup(const std::string& base, const std::string& child) {
    return imagenets::frames::toIsometry(buffer_.lookupTransform(base, child, ros::Time(0)).transform, child);
  }

 private:
  boost::function<void(const tf2_msgs::TFMessageConstPtr&)> add(bool is_static) {
    return [this, is_static](const tf2_msgs::TFMessageConstPtr& m) {
      for (const auto& t : m->transforms) buffer_.setTransform(t, "calibrated_urdf", is_static);
    };
  }
  ros::NodeHandle nh_;
  tf2::BufferCore buffer_;  // thread-safe; before the subscribers, which fill it
  ros::Publisher joints_;
  ros::Subscriber tf_sub_, static_sub_;
  std::unique_ptr<ChildProcess> process_;  // last: stopped first
};

// robot_state_publisher started on `urdf_file` gives the frames of the robot `expected`: base ->
// `head_link0` (the head's fixed point) at its head mount, and at given joint states (as the
// encoders read them) the left optical frame and the gripper marker, each to 1e-6.
inline void expectUrdfGivesTheFrames(const std::string& urdf_file, const robot_description::RobotModel& expected,
                                     const std::string& head_link0) {
  const auto& d = expected.description();
  UrdfStatePublisher publisher("/calibrated_urdf", urdf_file);
  ASSERT_TRUE(publisher.started());
  auto expectNear = [&](const std::string& child, const Eigen::Isometry3d& want) {
    const Eigen::Isometry3d seen = publisher.lookup(d.base_frame, child);
    EXPECT_LT((seen.translation() - want.translation()).norm(), 1e-6) << child;
    EXPECT_LT(Eigen::AngleAxisd(seen.linear().transpose() * want.linear()).angle(), 1e-6) << child;
  };
  ASSERT_TRUE(waitFor([&] { return publisher.canTransform(d.base_frame, head_link0); }, 60))
      << "robot_state_publisher published no " << d.base_frame << " -> " << head_link0 << " from " << urdf_file;
  expectNear(head_link0, expected.headBase());

  sensor_msgs::JointState js;
  js.name = d.arm.names();
  for (const auto& n : d.head.names()) js.name.push_back(n);
  std::vector<double> arm = d.arm_calibration_pose, head = {0.2, 0.4};
  for (size_t i = 0; i < arm.size(); ++i) arm[i] += 0.05 * (i + 1);
  js.position = arm;
  js.position.insert(js.position.end(), head.begin(), head.end());
  ASSERT_TRUE(publisher.waitForFrames(d.base_frame, {d.left_camera.frame, d.marker.frame}, js, 60))
      << "robot_state_publisher published no moving joints from " << urdf_file;
  expectNear(d.left_camera.frame, expected.leftCamera(head));
  expectNear(d.marker.frame, expected.marker(arm));
}
