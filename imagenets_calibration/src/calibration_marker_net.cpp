#include "imagenets_calibration/calibration_marker_net.h"

#include "imagenets_calibration/calibration_msgs.h"

#include <limits>
#include <stdexcept>

#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>

#include "robot_description/robot_model.h"
#include "imagenets/vision/frames.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/executor.h"
#include "imagenets/net_writer.h"
#include "imagenets/package_file.h"
#include "imagenets/registry.h"

namespace imagenets_calibration {

std::string CalibrationMarkerNet::defaultNetPath() {
  return imagenets::packageFile("imagenets_blocks", "config/nets/calibration_marker_detection.yaml");
}

imagenets::NetSpec CalibrationMarkerNet::specWithSearch(const std::function<void(imagenets::NetSpec&)>& edit_search) {
  imagenets::NetSpec spec = imagenets::parseNetFile(defaultNetPath());
  const imagenets::BlockInfo* sub_net = imagenets::BlockRegistry::instance().find("imagenets/SubNet");
  for (auto& b : spec.blocks) {
    for (auto& p : b.properties) {  // by its name or a former one
      if (imagenets::BlockRegistry::instance().find(b.type) != sub_net || p.name != "net") continue;
      imagenets::NetSpec search = imagenets::parseNetFile(spec.base_dir + "/" + p.text);
      edit_search(search);
      p.name = "net_yaml";
      p.text = imagenets::writeNetText(search);
    }
  }
  return spec;
}

CalibrationMarkerNet::CalibrationMarkerNet(const std::string& net_path, int threads) {
  imagenets::ExecutorOptions options;
  options.threads = threads;
  executor_ = imagenets::Executor::loadFile(net_path, options);
}

CalibrationMarkerNet::CalibrationMarkerNet(const imagenets::NetSpec& spec, int threads) {
  imagenets::ExecutorOptions options;
  options.threads = threads;
  executor_ = std::make_unique<imagenets::Executor>(imagenets::Net::build(spec), options);
}

CalibrationMarkerNet::~CalibrationMarkerNet() = default;

MarkerObservation CalibrationMarkerNet::detect(const sensor_msgs::ImageConstPtr& image,
                                               const sensor_msgs::CameraInfo& info,
                                               const std::optional<Eigen::Isometry3d>& predicted) {
  executor_->setInput("image.value", image);
  executor_->setInput("camera_info.value", boost::make_shared<const sensor_msgs::CameraInfo>(info));
  if (predicted) {
    auto pose = boost::make_shared<geometry_msgs::PoseStamped>();
    pose->header = info.header;
    pose->pose = imagenets::frames::toPose(*predicted);
    executor_->setInput("predicted_pose.value", boost::shared_ptr<const geometry_msgs::PoseStamped>(pose));
  } else {
    executor_->setInput("predicted_pose.value", imagenets::Value());
  }
  // A marker that is not there is no error (no region and threshold give a score); a block that
  // fails, even inside the feedback's trials (e.g. the region for an image of another size), is.
  // (The sub-net's blocks fail only on their configuration, which loading the net checks.)
  const auto& nodes = executor_->net().nodes();
  std::vector<size_t> failures_before;
  for (const auto& n : nodes) failures_before.push_back(executor_->stats(n.name).failures);
  const imagenets::RunReport report = executor_->run();
  const auto region = lastRegionTrace();
  const bool not_found = region && !region->found;
  std::string message;
  for (size_t i = 0; i < nodes.size() && message.empty(); ++i) {
    const auto stats = executor_->stats(nodes[i].name);
    if (stats.failures > failures_before[i]) message = "block '" + nodes[i].name + "': " + stats.last_error;
  }
  if (message.empty() && !report.ok() && !not_found) {
    for (const auto& f : report.failed) message += (message.empty() ? "" : "; ") + f;
  }
  if (!message.empty()) throw std::invalid_argument(executor_->net().origin() + ": " + message);
  // (Downstream of the failed region search nothing ran: its outputs may be the previous run's.)
  if (not_found) return observationOf(nullptr, nullptr, report.failed.front());
  return observationOf(executor_->output<imagenets::MarkerDetection>("detection.value").get(), lastTrace().get(),
                       report.ok() ? "marker lost when its corners were refined" : report.failed.front());
}

boost::shared_ptr<const imagenets::FeedbackTrace> CalibrationMarkerNet::lastRegionTrace() const {
  return executor_->output<imagenets::FeedbackTrace>("region.feedback_trace");
}

boost::shared_ptr<const imagenets::FeedbackTrace> CalibrationMarkerNet::lastTrace() const {
  return executor_->output<imagenets::FeedbackTrace>("feedback_trace.value");
}

}  // namespace imagenets_calibration
