// Robust marker detection (paper 3.4, Fig. 3.3) on one camera image, as the calibration uses it:
// the binarisation threshold is swept coarse-to-fine and the detection with the best pattern
// confidence is kept (the net's feedback loop, here in code so the node runs it for both images
// in parallel without a net file). A predicted marker pose (from the nominal model) restricts the
// search to a region of interest and resolves the planar-pose ambiguity (IPPE's two solutions).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "friend_calibration/calibration.h"
#include "imagenets/blocks/marker.h"

namespace friend_calibration {

struct RobustDetectionOptions {
  int coarse_from = 30, coarse_to = 210, coarse_step = 30;  // threshold sweep, gray levels
  int fine_radius = 10, fine_step = 5;                      // refinement around the best
  double min_confidence = 0.6;
  // Stop early: the region's Otsu threshold is tried first, and a detection there with at least
  // this pattern confidence and (refined) reprojection error at most `good_reprojection_px` is
  // kept without sweeping (0 = always sweep). A disturbed marker fails these and gets the sweep.
  double good_confidence = 0.95;
  double good_reprojection_px = 0.1;
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
