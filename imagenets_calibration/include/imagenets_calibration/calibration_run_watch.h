// Watches one run of a calibration net for the node (through CalibrationNetInterface, so only
// what the net declares): the action's feedback (the block that started, and with an uncertainty
// target the bounds after each pose added), each sample's images and sample as the sample net
// made them, and the time the images' processing took.
#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>

#include "imagenets/run_events.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/calibration_net_interface.h"
#include "imagenets_calibration_msgs/CalibrateFeedback.h"

namespace imagenets_calibration {

// The fixed point's 3-sigma bounds (0 without a covariance) into a response, result or feedback.
template <class Out>
void fillBounds(Out& out, const Result& r) {
  out.uncertainty = r.has_covariance ? 3 * r.sigmaTranslation() : 0.0;
  out.uncertainty_rotation = r.has_covariance ? 3 * r.sigmaRotation() : 0.0;
}

class CalibrationRunWatch {
 public:
  using Progress = std::function<void(const imagenets_calibration_msgs::CalibrateFeedback&)>;
  // Called after each repetition that made a sample, with the images it was measured on.
  using SampleTaken = std::function<void(const CameraImages&, const Sample&)>;
  // The image processing's time over all samples, s: per sample the slowest camera's (they are
  // processed in parallel), as wall time and as the processing threads' CPU time.
  struct DetectionTime {
    double wall = 0, cpu = 0;
  };

  // `samples`: N for the feedback (with a target the maximum); `requested`: the poses taken in any
  // case (with a target, each one after them is fed back with the bounds reached).
  CalibrationRunWatch(const CalibrationNetInterface& net, int samples, int requested, Progress progress,
                      SampleTaken sample_taken);
  // The executor's observer (thread-safe).
  void operator()(const imagenets::RunEvent& e);

  int done() const;
  DetectionTime detectionTime() const;
  CameraImages lastImages() const;  // of the last sample taken

 private:
  imagenets_calibration_msgs::CalibrateFeedback feedback(int k, const std::string& stage) const;
  void onStarted(const imagenets::RunEvent& e);
  void onFinished(const imagenets::RunEvent& e);
  void onRepetition(const imagenets::RunEvent& e);
  // With a target: the bounds the until net has just reached, fed back.
  void feedUncertainty(int index);
  // The sample net's sample and images after a repetition; per camera its processing time.
  void takeSample(const std::vector<imagenets::BlockStats>& per_camera);

  const CalibrationNetInterface& net_;
  const int samples_, requested_;
  Progress progress_;
  SampleTaken sample_taken_;
  std::set<std::string> stages_;                 // the net's own blocks fed back when they start
  std::map<std::string, std::vector<size_t>> cameras_of_block_;  // "samples/<block>" -> the cameras it serves
  mutable std::mutex mutex_;
  int done_ = 0;
  std::vector<imagenets::BlockStats> current_;  // per camera: the current sample's processing
  DetectionTime time_;
  CameraImages last_images_;
  boost::shared_ptr<const imagenets_calibration_msgs::CalibrationResult> last_until_result_;
};

}  // namespace imagenets_calibration
