// Runs the robust marker detection net (config/nets/robust_marker_detection.yaml, paper Fig. 3.3)
// on images held in memory: the net's `source` and `camera` blocks are taken out and their
// consumers (gray.image, detector.camera_info) fed directly. The threshold block keeps its feedback
// as the net writes it (the default: what `imagenets detect` runs), gets a plain range instead, or
// gets a fixed threshold and no feedback.
#pragma once

#include <memory>
#include <string>

#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

namespace imagenets {

class Executor;

namespace marker {

struct ThresholdMode {
  enum class Kind { AsWritten, Range, Fixed };
  Kind kind = Kind::AsWritten;
  bool feedback() const { return kind != Kind::Fixed; }
  double from = 40, to = 80, step = 1;  // Range: the candidates (no `initial`, no `good_enough`)
  std::string search = "exhaustive";    // Range: or coarse_to_fine
  bool parallel = true;                 // AsWritten, Range: feedback trials in parallel
  int fixed = 40;                       // Fixed: the threshold
};

class MarkerDetectionNet {
 public:
  // Throws NetError / std::runtime_error naming the file for a bad net or marker file.
  MarkerDetectionNet(const std::string& net_path, const std::string& marker_path, const ThresholdMode& mode,
                     int threads = 1);
  ~MarkerDetectionNet();

  struct Result {
    imagenets::MarkerDetectionConstPtr detection;  // null if the net failed; `threshold` filled in
    imagenets::FeedbackTraceConstPtr trace;        // null without feedback
    std::string error;                             // the net's failures, empty when it ran
    double ms = 0;                                 // wall time of the run
  };
  // Not thread-safe: one net per thread (its executor runs feedback trials in parallel itself).
  Result run(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& camera_info);

 private:
  ThresholdMode mode_;
  std::unique_ptr<Executor> executor_;
};

}  // namespace marker
}  // namespace imagenets
