#include "marker_study/marker_net.h"

#include <chrono>
#include <limits>
#include <sstream>

#include <boost/filesystem.hpp>

#include "imagenets/executor.h"
#include "imagenets/net.h"

namespace imagenets {
namespace marker {

MarkerDetectionNet::MarkerDetectionNet(const std::string& net_path, const std::string& marker_path,
                                       const ThresholdMode& mode, int threads)
    : mode_(mode) {
  NetSpec spec = parseNetFile(net_path);
  // Feed the image and camera_info from memory instead of files.
  for (const char* fed : {"source", "camera"}) spec.removeBlock(fed);
  BlockSpec& threshold = spec.block("threshold");
  if (mode.feedback() && !threshold.feedback) throw std::runtime_error(net_path + ": block 'threshold' has no feedback");
  if (mode.kind == ThresholdMode::Kind::AsWritten) {
    threshold.feedback->parallel = mode.parallel;
  } else if (mode.kind == ThresholdMode::Kind::Range) {
    FeedbackSpec& f = *threshold.feedback;
    f.values.clear();
    for (double v = mode.from; v <= mode.to + 1e-9; v += mode.step) f.values.push_back(v);
    f.from = mode.from;
    f.to = mode.to;
    f.step = mode.step;
    f.search = mode.search;
    f.parallel = mode.parallel;
    f.initial.clear();
    f.good_enough.reset();
    f.coarse_step.reset();
    f.fine_radius.reset();
  } else {
    threshold.feedback.reset();
    threshold.setProperty("threshold", std::to_string(mode.fixed));
  }
  spec.block("detector").setProperty("marker", boost::filesystem::absolute(marker_path).string());
  ExecutorOptions options;
  options.threads = threads;
  executor_.reset(new Executor(Net::build(spec), options));
}

MarkerDetectionNet::~MarkerDetectionNet() = default;

MarkerDetectionNet::Result MarkerDetectionNet::run(const sensor_msgs::ImageConstPtr& image,
                                                   const sensor_msgs::CameraInfoConstPtr& camera_info) {
  Result result;
  const auto t0 = std::chrono::steady_clock::now();
  executor_->setInput("gray.image", image);
  executor_->setInput("detector.camera_info", camera_info);
  const RunReport report = executor_->run();
  result.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (mode_.feedback()) result.trace = executor_->output<FeedbackTrace>("threshold.feedback_trace");
  auto detection = boost::make_shared<imagenets::MarkerDetection>();
  if (result.trace && !result.trace->found) {
    // "No valid candidate": no threshold of the range found the marker. Not an error.
    detection->found = false;
    detection->confidence = 0.0;
    detection->threshold = std::numeric_limits<double>::quiet_NaN();
    detection->pose.orientation.w = detection->alternative_pose.orientation.w = 1.0;
    detection->header = image->header;
    result.detection = detection;
    return result;
  }
  if (!report.ok()) {
    std::ostringstream os;
    for (size_t i = 0; i < report.failed.size(); ++i) os << (i ? "; " : "") << report.failed[i];
    result.error = os.str();
    return result;
  }
  const auto out = executor_->output<imagenets::MarkerDetection>("detector.detection");
  if (!out) {
    std::ostringstream os;
    os << "the net produced no detector.detection";
    for (const auto& n : report.not_run) os << "; " << n;
    result.error = os.str();
    return result;
  }
  *detection = *out;
  detection->threshold = mode_.feedback() ? result.trace->chosen_value : mode_.fixed;
  result.detection = detection;
  return result;
}

}  // namespace marker
}  // namespace imagenets
