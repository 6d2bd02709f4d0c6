// A repeated sample sub-net also hands out all its samples as one message (`sample_all`,
// collectors.h), in repetition order: what SolveCalibration takes. The calibration's message types
// are known by name from load, so a net's SubNetInput / SubNetOutput can name them.
#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <imagenets_calibration_msgs/CalibrationSamples.h>

#include "imagenets/collectors.h"

namespace imagenets_calibration {
namespace blocks {
namespace {

imagenets::CollectorRegistration<imagenets_calibration_msgs::CalibrationSample, imagenets_calibration_msgs::CalibrationSamples> samples_collector(
    [](const std::vector<imagenets_calibration_msgs::CalibrationSample::ConstPtr>& items) {
      auto all = boost::make_shared<imagenets_calibration_msgs::CalibrationSamples>();
      for (const auto& s : items) all->samples.push_back(*s);
      return all;
    });

const bool types_known = [] {
  imagenets::PortType::of<imagenets_calibration_msgs::CalibrationPlan>();
  imagenets::PortType::of<imagenets_calibration_msgs::CalibrationResult>();
  imagenets::PortType::of<imagenets_calibration_msgs::MarkerObservation>();
  return true;
}();

}  // namespace
}  // namespace blocks
}  // namespace imagenets_calibration
