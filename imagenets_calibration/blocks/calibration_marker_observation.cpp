// A marker observation (found, pose, confidence, threshold, reprojection error, the 8 points, why
// not) from the outputs of the robust detection sub-net (config/nets/calibration_marker_detection.yaml
// run by imagenets/SubNet with max_failures 1, so "not found" is its `failure`, not an error).
#include <boost/make_shared.hpp>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <imagenets_calibration_msgs/MarkerObservation.h>
#include <std_msgs/String.h>

#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class CalibrationMarkerObservation : public imagenets::Block {
 public:
  CalibrationMarkerObservation() {
    addOptionalInput<imagenets::MarkerDetection>("detection", "the detection (points in full-image pixels)");
    addOptionalInput<imagenets::FeedbackTrace>("feedback_trace", "the threshold search (the chosen threshold)");
    addOptionalInput<std_msgs::String>("failure", "why the detection gave nothing (its sub-net's `failure`)");
    addOutput<imagenets_calibration_msgs::MarkerObservation>("observation", "the marker as the calibration keeps it");
  }

  void process(imagenets::Context& ctx) override {
    const auto detection = ctx.input<imagenets::MarkerDetection>("detection");
    const auto trace = ctx.input<imagenets::FeedbackTrace>("feedback_trace");
    const auto failure = ctx.input<std_msgs::String>("failure");
    const std::string why_not =
        failure ? failure->data : detection ? "marker lost when its corners were refined" : "the detection gave no result";
    auto o = boost::make_shared<imagenets_calibration_msgs::MarkerObservation>(
        toMsg(observationOf(detection.get(), trace.get(), why_not)));
    ctx.output("observation", o);
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::CalibrationMarkerObservation,
                         "imagenets/CalibrationMarkerObservation", "calibration",
                         "Marker observation of the calibration from the robust detection sub-net's outputs");
