#include "imagenets_calibration/bag_calibration.h"

#include <stdexcept>

#include <boost/filesystem.hpp>
#include <imagenets_calibration_msgs/CalibrationResult.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/net_wide_property.h"
#include "imagenets/package_file.h"
#include "imagenets_calibration/bag_samples.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets_calibration/robot_interfaces.h"

namespace imagenets_calibration {

BagCalibration calibrateFromBag(const BagCalibrationOptions& o) {
  if (o.bag.empty()) throw std::runtime_error("no bag file given");
  if (o.description.empty()) throw std::runtime_error("no robot description given (the robot's calibration YAML)");
  if (!boost::filesystem::exists(o.bag)) throw std::runtime_error(o.bag + ": no such bag file");
  // The bag's samples first: a bag that lacks a topic says so before any net runs (the plan and
  // the sample blocks then find them read, with these settings).
  const RobotModel model(robot_description::loadRobotDescription(o.description));
  BagSampleSettings bag_settings;
  // The stereo pair's topics as the robot's config names them (robot_interfaces.h); --set wins.
  if (!model.description().stereo_namespace.empty()) bag_settings.camera = model.description().stereo_namespace;
  auto number = [](const std::pair<std::string, std::string>& s) {
    try {
      size_t end = 0;
      const double v = std::stod(s.second, &end);
      if (end == s.second.size()) return v;
    } catch (const std::exception&) {
    }
    throw std::runtime_error("property '" + s.first + "': '" + s.second + "' is not a number");
  };
  for (const auto& s : o.settings) {
    if (s.first == "bag_camera") bag_settings.camera = s.second;
    if (s.first == "bag_joint_states") bag_settings.joint_states = s.second;
    if (s.first == "still_time") bag_settings.still_time = number(s);
    if (s.first == "still_tolerance") bag_settings.still_tolerance = number(s);
    if (s.first == "max_stereo_offset") bag_settings.max_stereo_offset = number(s);
    if (s.first == "max_joint_state_age") bag_settings.max_joint_state_age = number(s);
  }
  BagCalibration out;
  out.samples = readBagSamples(boost::filesystem::absolute(o.bag).string(), sampleJoints(model), bag_settings)->report;
  const std::string net = o.net.empty() ? imagenets::packageFile("imagenets_calibration", "config/nets/calibration.yaml") : o.net;
  const std::string sample_net =
      o.sample_net.empty() ? imagenets::packageFile("imagenets_calibration", "config/nets/calibration_sample_bag.yaml") : o.sample_net;
  // The node's net, its sample net swapped as the node swaps in the replay's.
  imagenets::NetSpec spec = imagenets::parseNetFile(net);
  imagenets::BlockSpec* samples = spec.findBlock("samples");
  if (!samples || !samples->findSetting("net")) {
    throw std::runtime_error(net + ": no block 'samples' with a property 'net' (the sample net to run per sample)");
  }
  samples->setProperty("net", sample_net);
  imagenets::Executor exec(imagenets::Net::build(spec));
  auto setAll = [&](const std::string& property, const std::string& text, bool paths_only) {
    const auto set = imagenets::setPropertyInNetTree(
        exec, property, text, [&](const imagenets::PropertySpec& p) { return !paths_only || p.isPath(); });
    if (set.empty()) throw std::runtime_error(net + ": no block of the net or its sub-nets has a property '" + property + "'");
  };
  setAll("description", boost::filesystem::absolute(o.description).string(), true);
  applyRobotInterfaces(model.description(), exec);
  for (const auto& s : o.settings) setAll(s.first, s.second, false);
  exec.setPropertyText("plan", "method", o.method);
  exec.setPropertyText("plan", "bag", boost::filesystem::absolute(o.bag).string());

  const imagenets::RunReport report = exec.runAll();
  if (!report.ok()) throw std::runtime_error(exec.net().origin() + ": " + report.failed.front());
  const auto result = exec.output<imagenets_calibration_msgs::CalibrationResult>("result.value");
  if (!result) throw std::runtime_error(exec.net().origin() + ": the net gave no result");
  out.result = fromMsg(*result);
  return out;
}

}  // namespace imagenets_calibration
