// Camera models from ROS camera-info files: the YAML that camera_calibration and
// camera_info_manager write (or their INI format), read with Debian's camera_calibration_parsers.
#pragma once

#include <string>

#include <sensor_msgs/CameraInfo.h>

namespace imagenets {

// Reads `path`; throws std::runtime_error naming the file and what is wrong with it. A YAML file's
// matrices are checked first (rows x cols numbers, the shapes ROS uses): the parser asserts on a
// mismatch, which would abort the whole process (found by fuzzing, test/fuzz/regressions/camera_info).
sensor_msgs::CameraInfo readCameraInfo(const std::string& path, std::string* camera_name = nullptr);

}  // namespace imagenets
