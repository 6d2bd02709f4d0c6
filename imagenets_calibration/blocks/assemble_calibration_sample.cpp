// One calibration sample's raw measurements: the joint readings when the images were taken and
// the marker observations of the cameras measured with -- the stereo pair's two, or the mono
// camera's one (imagenets_calibration::Sample, not yet solved).
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
    addOptionalInput<imagenets_calibration_msgs::MarkerObservation>("left", "marker in the left image");
    addOptionalInput<imagenets_calibration_msgs::MarkerObservation>("right", "marker in the right image (right camera frame)");
    addOptionalInput<imagenets_calibration_msgs::MarkerObservation>("mono", "marker in the mono camera's image (its frame)");
    addInput<sensor_msgs::Image>("image", "an image of the sample (its stamp is the sample's time)");
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
    bool any = false;
    for (const char* camera : {"left", "right", "mono"}) {
      const auto o = ctx.input<imagenets_calibration_msgs::MarkerObservation>(camera);
      if (!o) continue;
      any = true;
      (std::string(camera) == "left" ? sample->left : std::string(camera) == "right" ? sample->right : sample->mono) = *o;
    }
    if (!any) throw imagenets::BlockError("inputs 'left', 'right', 'mono': none has an observation (link a camera's)");
    sample->stamp = ctx.input<sensor_msgs::Image>("image")->header.stamp.toSec();
    sample->fusion = "none";
    sample->marker_in_left.orientation.w = sample->fixed_point.orientation.w = 1;
    ctx.output("sample", sample);
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::AssembleCalibrationSample, "imagenets/AssembleCalibrationSample",
                         "calibration", "A calibration sample: joint readings and the cameras' marker observations");
