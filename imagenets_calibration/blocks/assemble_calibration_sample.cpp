// One calibration sample's raw measurements: the joint readings when the images were taken and
// the marker observations of both cameras (imagenets_calibration::Sample, not yet solved).
#include <boost/make_shared.hpp>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>

#include "calibration_ports.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets/blocks/robot.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class AssembleCalibrationSample : public imagenets::Block {
 public:
  AssembleCalibrationSample() {
    addInput<sensor_msgs::JointState>("arm_joints", "arm joint_states (encoder readings)");
    addInput<sensor_msgs::JointState>("head_joints", "head joint_states");
    addInput<imagenets_calibration_msgs::MarkerObservation>("left", "marker in the left image");
    addInput<imagenets_calibration_msgs::MarkerObservation>("right", "marker in the right image (right camera frame)");
    addInput<sensor_msgs::Image>("image", "the left image (its stamp is the sample's time)");
    addOutput<imagenets_calibration_msgs::CalibrationSample>("sample", "the raw sample");
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
  }

  void process(imagenets::Context& ctx) override {
    const auto& d = robotModel(ctx.property<std::string>("description")).description();
    auto sample = boost::make_shared<imagenets_calibration_msgs::CalibrationSample>();
    sample->arm_q = imagenets::blocks::jointPositions(*ctx.input<sensor_msgs::JointState>("arm_joints"), d.arm.names(),
                                                      "arm_joints");
    sample->head_q = imagenets::blocks::jointPositions(*ctx.input<sensor_msgs::JointState>("head_joints"),
                                                       d.head.names(), "head_joints");
    sample->left = *ctx.input<imagenets_calibration_msgs::MarkerObservation>("left");
    sample->right = *ctx.input<imagenets_calibration_msgs::MarkerObservation>("right");
    sample->stamp = ctx.input<sensor_msgs::Image>("image")->header.stamp.toSec();
    sample->fusion = "none";
    sample->marker_in_left.orientation.w = sample->fixed_point.orientation.w = 1;
    ctx.output("sample", sample);
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::AssembleCalibrationSample, "imagenets/AssembleCalibrationSample",
                         "calibration", "A calibration sample: joint readings and both marker observations");
