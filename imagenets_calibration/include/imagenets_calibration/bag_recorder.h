// A rosbag written as a whole or not at all: messages go to FILE.tmp.bag beside FILE, which
// commit() renames to FILE; a recorder destroyed without commit() (a failed calibration) removes
// its temporary file, so a previous bag at FILE is never lost to a failed run. rosbag's headers
// stay in the .cpp.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>

namespace rosbag {
class Bag;
}

namespace imagenets_calibration {

class BagRecorder {
 public:
  // Thread-safe: the node writes samples and tf from different threads.
  // Opens the temporary file (creating FILE's directory); throws std::runtime_error naming it.
  explicit BagRecorder(const std::string& file);
  ~BagRecorder();
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  void write(const std::string& topic, const ros::Time& time, const sensor_msgs::Image& msg);
  void write(const std::string& topic, const ros::Time& time, const sensor_msgs::CameraInfo& msg);
  void write(const std::string& topic, const ros::Time& time, const sensor_msgs::JointState& msg);
  void write(const std::string& topic, const ros::Time& time, const tf2_msgs::TFMessage& msg);
  // Closes the bag and puts it in place of FILE; throws std::runtime_error naming the file.
  void commit();
  const std::string& file() const { return file_; }

 private:
  std::string file_, tmp_;
  std::mutex mutex_;
  std::unique_ptr<rosbag::Bag> bag_;
};

}  // namespace imagenets_calibration
