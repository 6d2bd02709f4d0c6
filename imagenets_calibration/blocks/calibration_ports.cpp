#include "calibration_ports.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

#include "imagenets/blocks/robot.h"

namespace imagenets_calibration {
namespace blocks {

const RobotModel& robotModel(const std::string& path, const std::string& calibration_camera) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, std::string>, std::unique_ptr<RobotModel>> cache;
  const auto& description = imagenets::blocks::robotDescription(path);
  std::lock_guard<std::mutex> lock(mutex);
  auto& model = cache[{description.source, calibration_camera}];
  if (!model) {
    try {
      model = std::make_unique<RobotModel>(
          calibration_camera.empty() ? description
                                     : robot_description::withCalibrationCamera(description, calibration_camera,
                                                                                "property 'calibration_camera'"));
    } catch (const std::runtime_error& e) {
      throw imagenets::BlockError(e.what());
    }
  }
  return *model;
}

imagenets::PropertySpec calibrationCameraProperty() {
  imagenets::PropertySpec p("calibration_camera", imagenets::PropertyTraits<std::string>::kind, std::string(),
                            "the camera measured with: stereo, mono, or empty: the description's calibration_camera");
  return p;
}

int sampleIndex(const imagenets::Context& ctx, const imagenets_calibration_msgs::CalibrationPlan& plan) {
  const auto repetition = ctx.input<std_msgs::Int32>("repetition");
  const int k = repetition ? repetition->data : ctx.property<int>("index");
  // With an uncertainty target the plan holds poses beyond `samples`, up to `max_samples`.
  const int planned = std::max(plan.samples, plan.max_samples);
  if (k < 0 || k >= planned) {
    throw imagenets::BlockError(std::string(repetition ? "input 'repetition'" : "property 'index'") + ": sample " +
                                std::to_string(k) + " of a plan of " + std::to_string(planned) + " samples");
  }
  return k;
}

namespace {

// Each bag setting once, as a property: the declaration and the reading both walk these lists.
struct BagText {
  const char* name;
  std::string BagSampleSettings::*field;
  const char* description;
};
struct BagNumber {
  const char* name;
  double BagSampleSettings::*field;
  const char* description;
  double max;
};
const BagText kBagTexts[] = {
    {"bag_camera", &BagSampleSettings::camera, "bag: camera namespace NS/{left,right}/{image_raw,camera_info}"},
    {"bag_joint_states", &BagSampleSettings::joint_states, "bag: JointState topic"},
};
const BagNumber kBagNumbers[] = {
    {"still_time", &BagSampleSettings::still_time, "bag: s no joint may move before and after an image taken as a sample",
     60.0},
    {"still_tolerance", &BagSampleSettings::still_tolerance,
     "bag: rad (m) a joint may change and still count as not moving", 1.0},
    {"max_stereo_offset", &BagSampleSettings::max_stereo_offset, "bag: s between the left and right image stamps of a pair",
     1.0},
    {"max_joint_state_age", &BagSampleSettings::max_joint_state_age, "bag: s from an image to each joint's nearest reading",
     10.0},
};

}  // namespace

std::vector<imagenets::PropertySpec> bagSampleProperties() {
  using imagenets::PropertySpec;
  using imagenets::PropertyTraits;
  const BagSampleSettings d;
  std::vector<PropertySpec> p;
  for (const BagText& t : kBagTexts) p.emplace_back(t.name, PropertyTraits<std::string>::kind, d.*t.field, t.description);
  for (const BagNumber& n : kBagNumbers) {
    p.emplace_back(n.name, PropertyTraits<double>::kind, d.*n.field, n.description);
    p.back().range(0.0, n.max);
  }
  return p;
}

BagSampleSettings bagSampleSettings(const imagenets::Context& ctx) {
  BagSampleSettings s;
  for (const BagText& t : kBagTexts) s.*t.field = ctx.property<std::string>(t.name);
  for (const BagNumber& n : kBagNumbers) s.*n.field = ctx.property<double>(n.name);
  return s;
}

}  // namespace blocks
}  // namespace imagenets_calibration
