// Whether a calibration is as certain as its plan asks (the Calibrate request's
// target_uncertainty / target_uncertainty_rotation): the stop condition of the calibration's
// "more poses until certain" (calibration_target.yaml, the sample sub-net's until net).
#include <boost/make_shared.hpp>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <std_msgs/Bool.h>

#include "calibration_ports.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class CalibrationTargetMet : public imagenets::Block {
 public:
  CalibrationTargetMet() {
    addInput<imagenets_calibration_msgs::CalibrationPlan>("plan", "the plan (its uncertainty targets)");
    addInput<imagenets_calibration_msgs::CalibrationResult>("result", "the calibration so far");
    addOutput<std_msgs::Bool>("met", "the fixed point's 3-sigma bounds are within the plan's targets");
  }

  void process(imagenets::Context& ctx) override {
    const auto plan = ctx.input<imagenets_calibration_msgs::CalibrationPlan>("plan");
    const Result r = fromMsg(*ctx.input<imagenets_calibration_msgs::CalibrationResult>("result"));
    auto met = boost::make_shared<std_msgs::Bool>();
    met->data = r.withinUncertaintyTarget(plan->target_uncertainty, plan->target_uncertainty_rotation);
    ctx.output("met", met);
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::CalibrationTargetMet, "imagenets/CalibrationTargetMet",
                         "calibration", "Whether a calibration's 3-sigma bounds are within its plan's uncertainty targets");
