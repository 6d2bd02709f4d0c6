// The calibration samples a rosbag holds: one stereo pair (images + camera_info) with the arm and
// head joint positions per period in which the joints stood still. Works on the bags the
// calibration node records (~record_bag: exactly the measured samples) and on bags of plain
// `rosbag record` while the robot was moved by other means (teleoperation): there an image counts
// only when no joint moved around it, and of the images of one still period the middle one is
// taken. Whether the marker is seen is the detection's to say, downstream (the solve's rejections).
// The bag is read with rosbag's C++ API; its headers stay in the .cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>

namespace robot_description {
class RobotModel;
}

namespace imagenets_calibration {

struct BagSampleSettings {
  std::string camera = "stereo";              // NS/{left,right}/{image_raw,camera_info}, as GrabStereoPair
  std::string joint_states = "joint_states";  // sensor_msgs/JointState topic (groups may be separate messages)
  double still_time = 0.25;                   // s: no joint moved within this before and after the image
  double still_tolerance = 1e-4;              // rad (or m): what counts as not moving
  double max_stereo_offset = 0.005;           // s: left and right image stamps at most this apart
  double max_joint_state_age = 0.25;          // s: each joint's nearest reading at most this far from the image
  // Topic names as a bag stores them (leading '/'): image_raw / camera_info of `side` (left, right).
  std::string imageTopic(const std::string& side) const;
  std::string infoTopic(const std::string& side) const;
  std::string jointStatesTopic() const;
};

struct BagStereoSample {
  sensor_msgs::ImageConstPtr left, right;
  sensor_msgs::CameraInfoConstPtr left_info, right_info;
  sensor_msgs::JointStatePtr joints;  // the requested joints at the image time (stamp: the left image's)
};

struct BagSamples {
  std::string file;
  std::vector<BagStereoSample> samples;
  // "10 samples from 10 stereo pairs (...); skipped: 3 pairs while a joint moved (first at t=...)".
  std::string report;
};

// The joints a sample needs: the arm's, then the head's (the description's names).
std::vector<std::string> sampleJoints(const robot_description::RobotModel& model);

// The samples of `file` for the joints `joints` (arm and head, by name). Read once per file version
// and settings (every sample of a calibration asks). Throws std::runtime_error naming the file and,
// for a bag without a needed topic, the topic (and the topics the bag has).
std::shared_ptr<const BagSamples> readBagSamples(const std::string& file, const std::vector<std::string>& joints,
                                                 const BagSampleSettings& settings);

}  // namespace imagenets_calibration
