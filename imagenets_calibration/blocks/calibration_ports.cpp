#include "calibration_ports.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

#include "imagenets/blocks/robot.h"

namespace imagenets_calibration {
namespace blocks {

const RobotModel& robotModel(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<RobotModel>> cache;
  const auto& description = imagenets::blocks::robotDescription(path);
  std::lock_guard<std::mutex> lock(mutex);
  auto& model = cache[description.source];
  if (!model) model = std::make_unique<RobotModel>(description);
  return *model;
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

std::vector<imagenets::PropertySpec> bagSampleProperties() {
  using imagenets::PropertySpec;
  using imagenets::PropertyTraits;
  const BagSampleSettings d;
  std::vector<PropertySpec> p;
  p.emplace_back("bag_camera", PropertyTraits<std::string>::kind, d.camera,
                 "bag: camera namespace NS/{left,right}/{image_raw,camera_info}");
  p.emplace_back("bag_joint_states", PropertyTraits<std::string>::kind, d.joint_states, "bag: JointState topic");
  p.emplace_back("still_time", PropertyTraits<double>::kind, d.still_time,
                 "bag: s no joint may move before and after an image taken as a sample");
  p.back().range(0.0, 60.0);
  p.emplace_back("still_tolerance", PropertyTraits<double>::kind, d.still_tolerance,
                 "bag: rad (m) a joint may change and still count as not moving");
  p.back().range(0.0, 1.0);
  p.emplace_back("max_stereo_offset", PropertyTraits<double>::kind, d.max_stereo_offset,
                 "bag: s between the left and right image stamps of a pair");
  p.back().range(0.0, 1.0);
  p.emplace_back("max_joint_state_age", PropertyTraits<double>::kind, d.max_joint_state_age,
                 "bag: s from an image to each joint's nearest reading");
  p.back().range(0.0, 10.0);
  return p;
}

BagSampleSettings bagSampleSettings(const imagenets::Context& ctx) {
  BagSampleSettings s;
  s.camera = ctx.property<std::string>("bag_camera");
  s.joint_states = ctx.property<std::string>("bag_joint_states");
  s.still_time = ctx.property<double>("still_time");
  s.still_tolerance = ctx.property<double>("still_tolerance");
  s.max_stereo_offset = ctx.property<double>("max_stereo_offset");
  s.max_joint_state_age = ctx.property<double>("max_joint_state_age");
  return s;
}

}  // namespace blocks
}  // namespace imagenets_calibration
