#include "imagenets_calibration/bag_recorder.h"

#include <cstdio>
#include <stdexcept>

#include <boost/filesystem.hpp>
#include <rosbag/bag.h>

namespace imagenets_calibration {

BagRecorder::BagRecorder(const std::string& file) : file_(file) {
  const boost::filesystem::path path(file);
  tmp_ = (path.parent_path() / (path.stem().string() + ".tmp.bag")).string();
  try {
    if (path.has_parent_path()) boost::filesystem::create_directories(path.parent_path());
    bag_ = std::make_unique<rosbag::Bag>();
    bag_->open(tmp_, rosbag::bagmode::Write);
  } catch (const std::exception& e) {
    bag_.reset();
    throw std::runtime_error("cannot record the bag " + file + " (temporary " + tmp_ + "): " + e.what());
  }
}

BagRecorder::~BagRecorder() {
  if (!bag_) return;
  try {
    bag_->close();
  } catch (const std::exception&) {
  }
  std::remove(tmp_.c_str());
}

void BagRecorder::write(const std::string& topic, const ros::Time& time, const sensor_msgs::Image& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (bag_) bag_->write(topic, time, msg);
}
void BagRecorder::write(const std::string& topic, const ros::Time& time, const sensor_msgs::CameraInfo& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (bag_) bag_->write(topic, time, msg);
}
void BagRecorder::write(const std::string& topic, const ros::Time& time, const sensor_msgs::JointState& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (bag_) bag_->write(topic, time, msg);
}
void BagRecorder::write(const std::string& topic, const ros::Time& time, const tf2_msgs::TFMessage& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (bag_) bag_->write(topic, time, msg);
}

void BagRecorder::commit() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!bag_) throw std::logic_error("BagRecorder::commit: already committed");
  try {
    bag_->close();
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write the bag " + tmp_ + ": " + e.what());
  }
  bag_.reset();
  if (std::rename(tmp_.c_str(), file_.c_str()) != 0) {
    std::remove(tmp_.c_str());
    throw std::runtime_error("cannot rename " + tmp_ + " to " + file_);
  }
}

}  // namespace imagenets_calibration
