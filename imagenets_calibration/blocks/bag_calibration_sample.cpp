// Sample k of a rosbag (the plan's bag file): the stereo pair and the arm and head joint readings
// of the bag's k-th still period (bag_samples.h), as the acquisition's motion, joint readings and
// grab give them live. The sample net calibration_sample_bag.yaml feeds them to the same
// prediction, detection and assembly as the live one, so a bag and a live run solve alike.
#include <boost/make_shared.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>

#include "calibration_ports.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class BagCalibrationSample : public imagenets::Block {
 public:
  BagCalibrationSample() {
    addInput<imagenets_calibration_msgs::CalibrationPlan>("plan", "a bag plan (its bag_file)");
    addOptionalInput<std_msgs::Int32>("repetition", "sample index k (a repeated sub-net's repetition); else `index`");
    addOutput<sensor_msgs::Image>("left_image", "left image of sample k");
    addOutput<sensor_msgs::Image>("right_image", "right image of sample k");
    addOutput<sensor_msgs::CameraInfo>("left_info", "left camera_info nearest to it");
    addOutput<sensor_msgs::CameraInfo>("right_info", "right camera_info nearest to it");
    addOutput<sensor_msgs::JointState>("arm_joints", "the arm's joints at the image (ReadJointStates' reading live)");
    addOutput<sensor_msgs::JointState>("head_joints", "the head's joints at the image");
    addProperty<int>("index", 0, "sample index when the input `repetition` has no value").range(0, 100000);
    for (const auto& p : bagSampleProperties()) addPropertySpec(p);
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
  }

  void process(imagenets::Context& ctx) override {
    const auto plan = ctx.input<imagenets_calibration_msgs::CalibrationPlan>("plan");
    if (plan->bag_file.empty()) throw imagenets::BlockError("input 'plan': not a bag plan (no bag file)");
    const int k = sampleIndex(ctx, *plan);
    const RobotModel& model = robotModel(ctx.property<std::string>("description"));
    std::shared_ptr<const BagSamples> bag;
    try {
      bag = readBagSamples(plan->bag_file, sampleJoints(model), bagSampleSettings(ctx));
    } catch (const std::exception& e) {
      throw imagenets::BlockError(std::string("input 'plan': bag file: ") + e.what());
    }
    if (static_cast<size_t>(k) >= bag->samples.size()) {
      throw imagenets::BlockError(plan->bag_file + ": no sample " + std::to_string(k) + " (" + bag->report + ")");
    }
    const BagStereoSample& s = bag->samples[k];
    // The joints by group, as two ReadJointStates give them live (arm first in s.joints).
    const size_t arm = model.description().arm.names().size();
    auto group = [&](size_t begin, size_t end) {
      auto js = boost::make_shared<sensor_msgs::JointState>();
      js->header = s.joints->header;
      js->name.assign(s.joints->name.begin() + begin, s.joints->name.begin() + end);
      js->position.assign(s.joints->position.begin() + begin, s.joints->position.begin() + end);
      return js;
    };
    ctx.output("left_image", s.left);
    ctx.output("right_image", s.right);
    ctx.output("left_info", s.left_info);
    ctx.output("right_info", s.right_info);
    ctx.output("arm_joints", group(0, arm));
    ctx.output("head_joints", group(arm, s.joints->name.size()));
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::BagCalibrationSample, "imagenets/BagCalibrationSample",
                         "calibration", "Sample k of a rosbag: stereo pair and joints where the robot stood still");
