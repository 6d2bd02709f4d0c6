// A repeated sample sub-net also hands out all its samples as one message (`sample_all`,
// collectors.h), in repetition order: what SolveCalibration takes. The calibration's message types
// are known by name from load, so a net's ExecutorInput / ExecutorOutput can name them.
#include <imagenets/CalibrationPlan.h>
#include <imagenets/CalibrationResult.h>
#include <imagenets/CalibrationSamples.h>

#include "imagenets/collectors.h"

namespace friend_calibration {
namespace blocks {
namespace {

imagenets::CollectorRegistration<imagenets::CalibrationSample, imagenets::CalibrationSamples> samples_collector(
    [](const std::vector<imagenets::CalibrationSample::ConstPtr>& items) {
      auto all = boost::make_shared<imagenets::CalibrationSamples>();
      for (const auto& s : items) all->samples.push_back(*s);
      return all;
    });

const bool types_known = [] {
  imagenets::PortType::of<imagenets::CalibrationPlan>();
  imagenets::PortType::of<imagenets::CalibrationResult>();
  imagenets::PortType::of<imagenets::MarkerObservation>();
  return true;
}();

}  // namespace
}  // namespace blocks
}  // namespace friend_calibration
