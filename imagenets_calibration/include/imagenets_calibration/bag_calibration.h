// A calibration from a rosbag, offline (no robot, no ROS master): the calibration net (as the node
// runs it: plan -> samples -> solve) with the bag sample net calibration_sample_bag.yaml in place
// of the acquisition, its plan reading the bag. `imagenets calibrate --bag` runs it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "imagenets_calibration/calibration.h"

namespace imagenets_calibration {

struct BagCalibrationOptions {
  std::string bag;
  std::string description;  // the robot's description YAML (required), as the node's ~description
  std::string net;          // the calibration net; "" = imagenets_calibration's calibration.yaml
  std::string sample_net;   // its bag sample net; "" = imagenets_calibration's calibration_sample_bag.yaml
  std::string method = "joint";
  // Further properties for every block of the net tree that has them (e.g. bag_camera, still_time,
  // min_valid_fraction), as written text.
  std::vector<std::pair<std::string, std::string>> settings;
};

struct BagCalibration {
  std::string samples;  // how many samples the bag held and why other images were skipped
  Result result;        // result.success false: result.message says why
};

// Throws std::runtime_error naming the file, block, topic or property that is wrong (a bag without
// a needed topic names the topic).
BagCalibration calibrateFromBag(const BagCalibrationOptions& options);

}  // namespace imagenets_calibration
