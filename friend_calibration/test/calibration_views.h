// The simulator's renderings of the calibration's views, as the calibration sees them: the joint
// method's ten poses, left and right camera, true geometry, default noise; twice, the second time
// with a spurious reflection near the marker in about half of the views (as the simulator's
// reflection fault). Shared by test/calibration_detection_net_test.cpp and
// bench/bench_calibration_detection.cpp so both judge the same images.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/vision/marker.h"

namespace imagenets_calibration {

struct CalibrationView {
  cv::Mat image;  // mono8 1024x768
  sensor_msgs::CameraInfo info;
  Eigen::Isometry3d truth, predicted;  // T_camera_marker: true, and from the nominal model
  bool reflection = false;
};

struct CalibrationViews {
  imagenets::marker::MarkerDescription marker;
  std::vector<CalibrationView> views;  // left, right of each pose in turn
};

CalibrationViews renderCalibrationViews();

}  // namespace imagenets_calibration
