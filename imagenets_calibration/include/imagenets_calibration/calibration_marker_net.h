// The calibration's robust marker detection (paper 3.4, Fig. 3.3), run as the net
// config/nets/calibration_marker_detection.yaml: the region around the predicted marker (the whole
// image when the marker is not near the prediction), in it the Otsu threshold first, stop when the
// detection is good enough, otherwise the threshold sweep coarse-to-fine -- all the engine's
// generic feedback, no hand-written search. Its options
// are the net's properties (e.g. executor().setPropertyText("detector", "marker", file)). One
// instance holds one loaded net; detect() is not reentrant (one instance per camera).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <imagenets/FeedbackTrace.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "imagenets_calibration/calibration.h"

namespace imagenets {
class Executor;
struct NetSpec;
}

namespace imagenets_calibration {

class CalibrationMarkerNet {
 public:
  // config/nets/calibration_marker_detection.yaml of this package.
  static std::string defaultNetPath();
  // That net with its threshold search (the sub-net calibration_marker_search.yaml) changed by
  // `edit_search` and inlined (`net_yaml`): variants for tests and benchmarks.
  static imagenets::NetSpec specWithSearch(const std::function<void(imagenets::NetSpec& search)>& edit_search);
  // Throws imagenets::NetError naming what is wrong in the net file. `threads` of the executor:
  // 1 runs everything on the calling thread.
  explicit CalibrationMarkerNet(const std::string& net_path = defaultNetPath(), int threads = 1);
  // From a parsed net (e.g. one with an option changed).
  CalibrationMarkerNet(const imagenets::NetSpec& spec, int threads);
  ~CalibrationMarkerNet();

  // `image`: mono8 (or colour); `predicted`: T_camera_marker from the nominal model. Never throws
  // for a marker that is not there (found = false with the reason); throws std::invalid_argument
  // naming the block for unusable inputs.
  MarkerObservation detect(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfo& info,
                           const std::optional<Eigen::Isometry3d>& predicted);
  // The last threshold search (in the chosen region): thresholds in the order tried, their scores,
  // why it stopped. None when no region held the marker.
  boost::shared_ptr<const imagenets::FeedbackTrace> lastTrace() const;
  // The last region search: the margins tried (300 px, then 0 = the whole image).
  boost::shared_ptr<const imagenets::FeedbackTrace> lastRegionTrace() const;
  imagenets::Executor& executor() { return *executor_; }

 private:
  std::unique_ptr<imagenets::Executor> executor_;
};

}  // namespace imagenets_calibration
