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

}  // namespace blocks
}  // namespace imagenets_calibration
