#include "friend_calibration/marker_measurement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "imagenets/vision/render.h"

namespace friend_calibration {
namespace {

struct Trial {
  imagenets::marker::Detection detection;
  int threshold = 0;
  bool valid = false;  // found, and the corners fit within the limit
  double score = 0.0;
};

}  // namespace

MarkerObservation detectMarkerRobustly(const cv::Mat& gray, const sensor_msgs::CameraInfo& info,
                                       const imagenets::marker::MarkerDescription& marker,
                                       const std::optional<Eigen::Isometry3d>& predicted,
                                       const RobustDetectionOptions& options) {
  namespace mk = imagenets::marker;
  if (gray.empty() || gray.type() != CV_8UC1) throw std::invalid_argument("image must be a non-empty mono8 image");
  imagenets::render::CameraModel camera = imagenets::render::CameraModel::fromCameraInfo(info);
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw std::invalid_argument("image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                                " but its camera_info says " + std::to_string(camera.width) + "x" +
                                std::to_string(camera.height));
  }
  // Region of interest around the predicted marker (the prediction is off by the calibration
  // error, a few centimetres: the margin covers it). K's principal point moves with the crop.
  const cv::Rect roi = predicted ? camera.regionAround(predicted->translation(), marker.size, options.roi_margin_px)
                                 : cv::Rect(0, 0, gray.cols, gray.rows);
  const cv::Mat view = gray(roi);
  const imagenets::render::CameraModel cropped = camera.cropped(roi);
  mk::DetectorOptions detector;
  detector.min_confidence = options.min_confidence;
  Eigen::Isometry3d hint;
  if (predicted) {
    hint = *predicted;
    detector.pose_hint = &hint;
  }
  // Each threshold once, in the order given; the best is the highest valid score (on a tie the one
  // tried first); `done` once one reaches good_score.
  std::vector<int> tried;
  Trial best;
  bool done = false;
  auto tryThreshold = [&](int t) {
    if (done || std::find(tried.begin(), tried.end(), t) != tried.end()) return;
    tried.push_back(t);
    cv::Mat binary;
    cv::threshold(view, binary, t, 255, cv::THRESH_BINARY);
    Trial trial;
    trial.threshold = t;
    trial.detection = mk::detect(view, binary, cropped, marker, detector);
    trial.valid = trial.detection.found && trial.detection.reprojection_error <= options.max_reprojection_px;
    if (!trial.valid) return;
    const double penalty = trial.detection.reprojection_error * options.reprojection_penalty;
    trial.score = trial.detection.confidence - penalty;
    if (!best.valid || trial.score > best.score) best = trial;
    done = options.good_score > 0 && trial.score >= options.good_score;
  };
  // The informed first guess: Otsu's threshold of the region (marker black and white against
  // the background). Under even light it is good at once, and the sweep is skipped.
  cv::Mat otsu_binary;
  tryThreshold(static_cast<int>(cv::threshold(view, otsu_binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU)));
  for (int t = options.coarse_from; t <= options.coarse_to; t += options.coarse_step) tryThreshold(t);
  if (best.valid && options.fine_step > 0) {
    const int centre = best.threshold;
    for (int k = -options.fine_radius / options.fine_step; k <= options.fine_radius / options.fine_step; ++k) {
      const int t = centre + k * options.fine_step;
      if (k != 0 && t >= options.coarse_from && t <= options.coarse_to) tryThreshold(t);
    }
  }
  MarkerObservation obs;
  if (!best.valid) {
    obs.reason = "marker '" + marker.name + "' not found in the " + std::to_string(roi.width) + "x" +
                 std::to_string(roi.height) + " region at any threshold " + std::to_string(options.coarse_from) + ".." +
                 std::to_string(options.coarse_to) + " with corners fitting within " +
                 std::to_string(options.max_reprojection_px) + " px";
    return obs;
  }
  obs.found = true;
  obs.confidence = best.detection.confidence;
  obs.threshold = best.threshold;
  obs.pose = best.detection.pose;
  obs.reprojection_error = best.detection.reprojection_error;
  for (const auto& p : best.detection.points) obs.points.emplace_back(p.x + roi.x, p.y + roi.y);
  return obs;
}

}  // namespace friend_calibration
