// The fuzz targets: every parser of outside input, called as the product calls it.
#include "fuzz_targets.h"

#include <stdexcept>

#include <camera_calibration_parsers/parse.h>
#include <sensor_msgs/CameraInfo.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "imagenets/param_text.h"
#include "imagenets_calibration/storage.h"
#include "robot_description/robot_model.h"
#include "imagenets/vision/marker.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/property.h"

namespace imagenets {
namespace fuzz {
namespace {

// Properties of every kind, with the ranges and choices blocks declare.
const std::vector<PropertySpec>& propertySpecs() {
  static const std::vector<PropertySpec> specs = [] {
    std::vector<PropertySpec> s;
    s.emplace_back("threshold", PropertyKind::Int, 128, "").range(0, 255);
    s.emplace_back("sigma", PropertyKind::Double, 1.0, "").range(0.0, 100.0);
    s.emplace_back("enabled", PropertyKind::Bool, true, "");
    s.emplace_back("mode", PropertyKind::String, std::string("otsu"), "").choices({"otsu", "fixed", "adaptive"});
    s.emplace_back("name", PropertyKind::String, std::string(""), "");
    s.emplace_back("offsets", PropertyKind::DoubleList, std::vector<double>{0, 0, 0}, "").range(-10, 10);
    return s;
  }();
  return specs;
}

// A net is built and run as `imagenets run` does; a block's failure comes back as the exception.
void buildAndRun(const NetSpec& spec) {
  Executor executor(Net::build(spec), ExecutorOptions{1});
  const RunReport report = executor.run();
  if (!report.ok()) throw std::runtime_error(report.failed.front());
}

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"net_file", "imagenets_blocks/config/nets/*.yaml",
       [](const std::string&, const std::string& file) { Net::build(parseNetFile(file)); }},
      {"net_rosparam", "imagenets_system_tests/fuzz/seeds/net_rosparam/*",
       // The rosparam form: a launch file's <rosparam> dict, as the SubNet nodelet gets it.
       [](const std::string& input, const std::string&) {
         int offset = 0;
         XmlRpc::XmlRpcValue value(input, &offset);
         if (!value.valid()) throw std::runtime_error("not an XML-RPC value");
         Net::build(parseNetText(paramToYaml(value), "rosparam /fuzz/net_yaml", "."));
       },
       false},
      {"property_text", "imagenets_system_tests/fuzz/seeds/property_text/*",
       [](const std::string& input, const std::string&) {
         for (const auto& spec : propertySpecs()) {
           try {
             spec.parse(input);
           } catch (const PropertyError&) {
           }
         }
       },
       false},
      {"camera_info", "imagenets_vision/config/cameras/*.yaml",
       [](const std::string&, const std::string& file) {
         NetSpec spec;
         spec.origin = "fuzz";
         spec.base_dir = ".";
         spec.blocks.push_back(BlockSpec{"camera", "imagenets/CameraInfoFile", {{"path", file, {}}}, {}, {}});
         buildAndRun(spec);
       }},
      {"marker", "imagenets_vision/config/markers/*.yaml",
       [](const std::string&, const std::string& file) { marker::MarkerDescription::load(file); }},
      {"robot_description", "robot_description/config/example/robot.yaml",
       [](const std::string&, const std::string& file) { robot_description::loadRobotDescription(file); }},
      {"calibration_file", "friend_calibration/test/*.yaml",
       [](const std::string&, const std::string& file) { imagenets_calibration::loadCalibration(file); }},
  };
  return all;
}

const Target& target(const std::string& name) {
  for (const auto& t : targets()) {
    if (t.name == name) return t;
  }
  throw std::out_of_range("no fuzz target '" + name + "'");
}

}  // namespace fuzz
}  // namespace imagenets
