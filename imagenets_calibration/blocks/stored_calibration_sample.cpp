// Sample k of a saved calibration file (the plan's replay file): the acquisition's replay twin,
// so a stored calibration is re-solved by the same net as a live one.
#include <map>
#include <mutex>

#include <boost/filesystem.hpp>
#include <boost/make_shared.hpp>

#include "calibration_ports.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets_calibration/storage.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class StoredCalibrationSample : public imagenets::Block {
 public:
  StoredCalibrationSample() {
    addInput<imagenets_calibration_msgs::CalibrationPlan>("plan", "a replay plan (its replay_file)");
    addOptionalInput<std_msgs::Int32>("repetition", "sample index k (a repeated sub-net's repetition); else `index`");
    addOutput<imagenets_calibration_msgs::CalibrationSample>("sample", "the stored sample k, as measured");
    addProperty<int>("index", 0, "sample index when the input `repetition` has no value").range(0, 100000);
  }

  void process(imagenets::Context& ctx) override {
    const auto plan = ctx.input<imagenets_calibration_msgs::CalibrationPlan>("plan");
    if (plan->replay_file.empty()) throw imagenets::BlockError("input 'plan': not a replay plan (no replay file)");
    const int k = sampleIndex(ctx, *plan);
    const auto samples = load(plan->replay_file);
    if (static_cast<size_t>(k) >= samples->size()) {
      throw imagenets::BlockError(plan->replay_file + ": no sample " + std::to_string(k) + " (it holds " +
                                  std::to_string(samples->size()) + ")");
    }
    ctx.output("sample", boost::make_shared<imagenets_calibration_msgs::CalibrationSample>(toMsg((*samples)[k])));
  }

 private:
  // The file's samples, read once per file version (every repetition reads one of them).
  std::shared_ptr<const std::vector<Sample>> load(const std::string& file) {
    std::time_t modified = 0;
    try {
      modified = boost::filesystem::last_write_time(file);
    } catch (const std::exception&) {
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!samples_ || file != file_ || modified != modified_) {
      try {
        samples_ = std::make_shared<const std::vector<Sample>>(loadCalibration(file).result.samples);
      } catch (const std::exception& e) {
        throw imagenets::BlockError(std::string("input 'plan': replay file: ") + e.what());
      }
      file_ = file;
      modified_ = modified;
    }
    return samples_;
  }

  std::mutex mutex_;
  std::string file_;
  std::time_t modified_ = 0;
  std::shared_ptr<const std::vector<Sample>> samples_;
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::StoredCalibrationSample, "imagenets/StoredCalibrationSample",
                         "calibration", "Sample k of a saved calibration file (replay without the robot)");
