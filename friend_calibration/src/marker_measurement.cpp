#include "friend_calibration/marker_measurement.h"

#include <algorithm>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/render.h"

namespace friend_calibration {
namespace {

struct Trial {
  imagenets::marker::Detection detection;
  int threshold = 0;
};

// Better: found, then higher confidence, then (nearly equal confidence) lower reprojection error:
// a threshold at which a reflection disturbs the border fits its corners worse.
bool better(const Trial& a, const Trial& b) {
  if (a.detection.found != b.detection.found) return a.detection.found;
  if (std::abs(a.detection.confidence - b.detection.confidence) > 0.05) {
    return a.detection.confidence > b.detection.confidence;
  }
  return a.detection.reprojection_error < b.detection.reprojection_error;
}

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
  cv::Rect roi(0, 0, gray.cols, gray.rows);
  if (predicted && options.roi_margin_px > 0 && predicted->translation().z() > 0.05) {
    const cv::Point2d c = camera.project(predicted->translation());
    const double side = camera.K(0, 0) * marker.size / predicted->translation().z();
    const int half = static_cast<int>(options.roi_margin_px + side);
    roi = cv::Rect(static_cast<int>(c.x) - half, static_cast<int>(c.y) - half, 2 * half, 2 * half) &
          cv::Rect(0, 0, gray.cols, gray.rows);
    if (roi.width < 16 || roi.height < 16) roi = cv::Rect(0, 0, gray.cols, gray.rows);
  }
  const cv::Mat view = gray(roi);
  imagenets::render::CameraModel cropped = camera;
  cropped.width = roi.width;
  cropped.height = roi.height;
  cropped.K(0, 2) -= roi.x;
  cropped.K(1, 2) -= roi.y;
  mk::DetectorOptions detector;
  detector.min_confidence = options.min_confidence;
  Eigen::Isometry3d hint;
  if (predicted) {
    hint = *predicted;
    detector.pose_hint = &hint;
  }
  // The sweep compares thresholds without the sub-pixel corner refinement (it hardly changes the
  // pattern confidence); the chosen threshold is then detected once more with it.
  mk::DetectorOptions sweep = detector;
  sweep.refine_passes = 0;
  auto detectIn = [&](const cv::Mat& binary, int t, const mk::DetectorOptions& o) {
    Trial trial;
    trial.threshold = t;
    trial.detection = mk::detect(view, binary, cropped, marker, o);
    return trial;
  };
  auto tryThreshold = [&](int t, const mk::DetectorOptions& o) {
    cv::Mat binary;
    cv::threshold(view, binary, t, 255, cv::THRESH_BINARY);
    return detectIn(binary, t, o);
  };
  // The informed first guess: Otsu's threshold of the region (marker black and white against
  // the background). Under even light it is as good as any other, and the sweep is skipped.
  cv::Mat otsu_binary;
  const int otsu = static_cast<int>(cv::threshold(view, otsu_binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
  Trial best = detectIn(otsu_binary, otsu, sweep);
  bool done = false;
  if (options.good_confidence > 0 && best.detection.found && best.detection.confidence >= options.good_confidence) {
    Trial refined = detectIn(otsu_binary, otsu, detector);
    if (refined.detection.found && refined.detection.reprojection_error <= options.good_reprojection_px) {
      best = refined;
      done = true;
    }
  }
  if (!done) {
    for (int t = options.coarse_from; t <= options.coarse_to; t += options.coarse_step) {
      Trial trial = tryThreshold(t, sweep);
      if (better(trial, best)) best = trial;
    }
    if (best.detection.found && options.fine_step > 0) {
      const int centre = best.threshold;
      for (int t = centre - options.fine_radius; t <= centre + options.fine_radius; t += options.fine_step) {
        if (t == centre || t < 1 || t > 254) continue;
        Trial trial = tryThreshold(t, sweep);
        if (better(trial, best)) best = trial;
      }
    }
    if (best.detection.found && detector.refine_passes > 0) best = tryThreshold(best.threshold, detector);
  }
  MarkerObservation obs;
  obs.found = best.detection.found;
  obs.confidence = best.detection.confidence;
  obs.threshold = best.threshold;
  if (!obs.found) {
    obs.reason = "marker '" + marker.name + "' not found in the " + std::to_string(roi.width) + "x" +
                 std::to_string(roi.height) + " region at any threshold " + std::to_string(options.coarse_from) + ".." +
                 std::to_string(options.coarse_to) + " (best confidence " + std::to_string(best.detection.confidence) + ")";
    return obs;
  }
  obs.pose = best.detection.pose;
  obs.reprojection_error = best.detection.reprojection_error;
  for (const auto& p : best.detection.points) obs.points.emplace_back(p.x + roi.x, p.y + roi.y);
  return obs;
}

}  // namespace friend_calibration
