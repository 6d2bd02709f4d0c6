#include "imagenets_calibration/calibration_run_watch.h"

#include <algorithm>
#include <cmath>

#include <ros/console.h>

#include "imagenets/net_port.h"
#include "imagenets_calibration/calibration_msgs.h"

namespace imagenets_calibration {

CalibrationRunWatch::CalibrationRunWatch(const CalibrationNetInterface& net, int samples, int requested,
                                         Progress progress, SampleTaken sample_taken)
    : net_(net),
      samples_(samples),
      requested_(requested),
      progress_(std::move(progress)),
      sample_taken_(std::move(sample_taken)),
      current_(net.cameras().size()) {
  for (const auto& node : net.executor().net().nodes()) {
    if (node.name != net.samplesBlock() && !dynamic_cast<const imagenets::NetPort*>(node.block.get())) {
      stages_.insert(node.name);
    }
  }
  for (size_t c = 0; c < net.imageBlocks().size(); ++c) {
    for (const std::string& block : net.imageBlocks()[c]) cameras_of_block_[net.samplesBlock() + "/" + block].push_back(c);
  }
  // The until net's result before this run is not one of its answers.
  last_until_result_ = net.untilResult();
}

imagenets_calibration_msgs::CalibrateFeedback CalibrationRunWatch::feedback(int k, const std::string& stage) const {
  imagenets_calibration_msgs::CalibrateFeedback f;
  f.sample = k;
  f.samples = samples_;
  f.stage = stage;
  return f;
}

void CalibrationRunWatch::operator()(const imagenets::RunEvent& e) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (e.kind == imagenets::RunEventKind::BlockStarted) {
    onStarted(e);
  } else if (e.kind == imagenets::RunEventKind::BlockFinished) {
    onFinished(e);
  } else if (e.kind == imagenets::RunEventKind::Repetition && e.block == net_.samplesBlock()) {
    onRepetition(e);
  }
}

void CalibrationRunWatch::onStarted(const imagenets::RunEvent& e) {
  if (!progress_) return;
  // Stage: the block that started: one of the sample net's (e.g. samples/motion, samples/grab)
  // or, after the samples, one of the calibration net's own (solve).
  const std::string prefix = net_.samplesBlock() + "/";
  const bool in_sample = e.block.rfind(prefix, 0) == 0 && e.block.find('/', prefix.size()) == std::string::npos;
  if (in_sample) progress_(feedback(done_ + 1, e.block));
  if (stages_.count(e.block) && done_ > 0) progress_(feedback(done_, e.block));
}

void CalibrationRunWatch::onFinished(const imagenets::RunEvent& e) {
  const auto cameras = cameras_of_block_.find(e.block);
  if (cameras == cameras_of_block_.end()) return;
  for (size_t c : cameras->second) {
    current_[c].last_ms += e.stats.last_ms;
    current_[c].last_cpu_ms += e.stats.last_cpu_ms;
  }
}

void CalibrationRunWatch::onRepetition(const imagenets::RunEvent& e) {
  done_ = e.index;
  const std::vector<imagenets::BlockStats> per_camera = current_;
  current_.assign(current_.size(), imagenets::BlockStats{});
  double wall = 0, cpu = 0;
  for (const auto& s : per_camera) {
    wall = std::max(wall, s.last_ms);
    cpu = std::max(cpu, s.last_cpu_ms);
  }
  time_.wall += wall / 1000.0;  // the cameras' images are processed in parallel
  time_.cpu += cpu / 1000.0;
  if (progress_ && e.index >= requested_ && e.index < samples_) feedUncertainty(e.index);
  if (e.stats.status == imagenets::BlockStatus::Ok) takeSample(per_camera);
}

void CalibrationRunWatch::feedUncertainty(int index) {
  // A result the until net did not have before: it has just solved the samples so far.
  const auto so_far = net_.untilResult();
  if (!so_far || so_far == last_until_result_) return;
  last_until_result_ = so_far;
  auto f = feedback(index, "uncertainty");
  fillBounds(f, fromMsg(*so_far));
  progress_(f);
  ROS_INFO("after %d poses: 3 sigma %.3f mm / %.4f deg", index, 1000 * f.uncertainty,
           f.uncertainty_rotation * 180 / M_PI);
}

void CalibrationRunWatch::takeSample(const std::vector<imagenets::BlockStats>& per_camera) {
  const auto msg = net_.sample();
  const CameraImages images = net_.images();
  if (!msg || images.empty()) return;  // e.g. a replay: no images
  const Sample s = fromMsg(*msg);
  std::string line;
  for (size_t c = 0; c < net_.cameras().size(); ++c) {
    const auto& camera = net_.cameras()[c];
    const MarkerObservation& o = observationOf(s, camera);
    char b[160];
    std::snprintf(b, sizeof b, "%s%s %s (conf %.2f, %.0f ms, CPU %.0f ms)", line.empty() ? "" : ", ", camera.c_str(),
                  o.found ? "found" : "not found", o.confidence, per_camera[c].last_ms, per_camera[c].last_cpu_ms);
    line += b;
  }
  ROS_INFO("sample %d/%d: %s", done_, samples_, line.c_str());
  last_images_ = images;
  if (sample_taken_) sample_taken_(images, s);
}

int CalibrationRunWatch::done() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return done_;
}

CalibrationRunWatch::DetectionTime CalibrationRunWatch::detectionTime() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return time_;
}

CameraImages CalibrationRunWatch::lastImages() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_images_;
}

}  // namespace imagenets_calibration
