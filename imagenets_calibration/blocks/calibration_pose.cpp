// The calibration pose of sample k of the plan (paper 4.2), as arm and head targets for MoveArm /
// MoveHead. Stage `approach`: where the arm comes from first (the paper's re-approach; the pose
// itself for the joint method); stage `target`: the pose.
#include <boost/make_shared.hpp>
#include <sensor_msgs/JointState.h>

#include "calibration_ports.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class CalibrationPose : public imagenets::Block {
 public:
  CalibrationPose() {
    addInput<imagenets_calibration_msgs::CalibrationPlan>("plan", "the calibration plan");
    addOptionalInput<std_msgs::Int32>("repetition", "sample index k (a repeated sub-net's repetition); else `index`");
    addOptionalInput<sensor_msgs::JointState>("after", "only after this (e.g. the approach's MoveArm.reached)");
    addOutput<sensor_msgs::JointState>("arm", "arm joint targets");
    addOutput<sensor_msgs::JointState>("head", "head joint targets (pan, tilt)");
    addProperty<int>("index", 0, "sample index when the input `repetition` has no value").range(0, 100000);
    addProperty<std::string>("stage", "target", "approach: where the arm comes from; target: the pose")
        .choices({"approach", "target"});
  }

  void process(imagenets::Context& ctx) override {
    const auto plan = ctx.input<imagenets_calibration_msgs::CalibrationPlan>("plan");
    if (!plan->replay_file.empty()) throw imagenets::BlockError("input 'plan': a replay plan has no poses");
    const int k = sampleIndex(ctx, *plan);
    if (static_cast<size_t>(k) >= plan->arm.size() || plan->arm.size() != plan->head.size() ||
        plan->arm.size() != plan->arm_approach.size()) {
      throw imagenets::BlockError("input 'plan': no pose for sample " + std::to_string(k));
    }
    const bool approach = ctx.property<std::string>("stage") == "approach";
    ctx.output("arm", boost::make_shared<sensor_msgs::JointState>(approach ? plan->arm_approach[k] : plan->arm[k]));
    ctx.output("head", boost::make_shared<sensor_msgs::JointState>(plan->head[k]));
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::CalibrationPose, "imagenets/CalibrationPose", "calibration",
                         "Arm and head targets of sample k of a calibration plan");
