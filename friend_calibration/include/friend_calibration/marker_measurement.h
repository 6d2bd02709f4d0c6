// Robust marker detection (paper 3.4, Fig. 3.3) on one camera image, as the calibration uses it,
// written by hand: the region's Otsu threshold first, stop as soon as a detection is good enough,
// otherwise the threshold sweep coarse-to-fine. A detection scores its pattern confidence
// penalised by how badly its (sub-pixel) corners fit the pose, and one that fits worse than a
// limit is rejected. The net config/nets/calibration_marker_detection.yaml (calibration_marker_net.h)
// declares the same with the engine's generic feedback (initial, good_enough, coarse_step,
// fine_radius) and ordinary blocks for the score; friend_calibration/test/calibration_marker_net_test.cpp
// shows they agree exactly. A predicted marker pose (from the nominal model) restricts the search
// to a region of interest and resolves the planar-pose ambiguity (IPPE's two solutions).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "friend_calibration/calibration.h"
#include "imagenets/vision/marker.h"

namespace friend_calibration {

struct RobustDetectionOptions {
  int coarse_from = 30, coarse_to = 210, coarse_step = 30;  // threshold sweep, gray levels
  // Then centre +- k * fine_step (k = 1 .. fine_radius / fine_step) around the best so far, within
  // coarse_from..coarse_to (fine_step 0: no fine pass).
  int fine_radius = 10, fine_step = 5;
  double min_confidence = 0.6;
  // Score of a detection: confidence - reprojection_penalty * its RMS reprojection error (px); a
  // reflection that bends the border fits worse. Above max_reprojection_px it is rejected.
  double reprojection_penalty = 1.0;
  double max_reprojection_px = 1.0;
  // Stop early: the first threshold (Otsu's first) whose detection scores at least this ends the
  // search (0 = always sweep). A disturbed marker misses it and gets the sweep.
  double good_score = 0.9;
  int roi_margin_px = 120;  // region of interest: predicted marker +- this (0 = whole image)
};

// `gray`: mono8 image; `info`: its camera_info; `predicted`: T_camera_marker expected from the
// nominal model (optional). Never throws for a marker that is not there (found = false with the
// reason); throws std::invalid_argument for unusable inputs (wrong size, bad camera_info).
MarkerObservation detectMarkerRobustly(const cv::Mat& gray, const sensor_msgs::CameraInfo& info,
                                       const imagenets::marker::MarkerDescription& marker,
                                       const std::optional<Eigen::Isometry3d>& predicted,
                                       const RobustDetectionOptions& options = RobustDetectionOptions());

}  // namespace friend_calibration
