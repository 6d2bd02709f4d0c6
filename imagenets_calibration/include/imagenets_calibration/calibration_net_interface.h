// What the calibration node needs of a calibration net (its ~net), found through the ports the
// nets declare (imagenets/SubNetOutput), never through the names of blocks inside them, so a net of
// one's own works when it has them:
//   the calibration net   output `result` (imagenets_calibration_msgs/CalibrationResult); the blocks
//                         `plan` and `solve` whose properties the node sets, and `samples`, the
//                         repeated imagenets/SubNet running the sample net (a replay swaps its net);
//   its sample net        output `sample` (imagenets_calibration_msgs/CalibrationSample); per camera
//                         `<camera>_image` (sensor_msgs/Image) with `<camera>_info`
//                         (sensor_msgs/CameraInfo), optional (a replay has none): the node draws
//                         the detection on them, records them, and times the image's processing as
//                         the sample net's blocks between that image and `sample`;
//   its until net         (optional) output `result`: fed back while poses are added for a target.
#pragma once

#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "imagenets/executor.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration_msgs/CalibrationResult.h"
#include "imagenets_calibration_msgs/CalibrationSample.h"

namespace imagenets_calibration {

// One camera's image of a sample and its calibration; `camera` as the sample net names it
// ("left", "right", "mono").
struct CameraImage {
  std::string camera;
  sensor_msgs::ImageConstPtr image;
  sensor_msgs::CameraInfoConstPtr info;
};
using CameraImages = std::vector<CameraImage>;

// The sample's observation in the camera the sample net names `camera`: "right" the right one,
// "mono" the mono camera's, any other the left (first) one.
const MarkerObservation& observationOf(const Sample& sample, const std::string& camera);

class CalibrationNetInterface {
 public:
  // Checks the net `exec` runs; throws naming the net file and the output (or block) missing or
  // of another type.
  explicit CalibrationNetInterface(imagenets::Executor& exec);

  imagenets::Executor& executor() const { return *exec_; }
  // The repeated sample sub-net's block: its repetitions are the samples.
  const std::string& samplesBlock() const { return samples_block_; }
  // The until net of the sample sub-net, or null.
  imagenets::Executor* untilNet() const;

  // The result of the last run (null: none).
  boost::shared_ptr<const imagenets_calibration_msgs::CalibrationResult> result() const;
  // The until net's result after its last run (null: none, or no until net).
  boost::shared_ptr<const imagenets_calibration_msgs::CalibrationResult> untilResult() const;
  // The sample net's values after a repetition: the sample (null: none) and the images with their
  // camera_info (only cameras that have both).
  boost::shared_ptr<const imagenets_calibration_msgs::CalibrationSample> sample() const;
  CameraImages images() const;

  // The cameras (from the sample net's `<camera>_image` outputs) and, for each, the sample net's
  // blocks that process its image (names as in the run events under samplesBlock()).
  const std::vector<std::string>& cameras() const { return cameras_; }
  const std::vector<std::vector<std::string>>& imageBlocks() const { return image_blocks_; }

 private:
  const imagenets::Executor* sampleNet() const;
  // The output `port` of `net`, checked for `type`; "" (no such output) when not `required`.
  static std::string outputOf(const imagenets::Net& net, const std::string& port, const std::string& type,
                              bool required, const std::string& what);
  void findCameras(const imagenets::Net& sample_net);

  imagenets::Executor* exec_;
  std::string samples_block_ = "samples";
  std::string result_, until_result_, sample_;  // "block.port" of each output ("" if none)
  std::vector<std::string> cameras_;
  std::vector<std::string> image_outputs_, info_outputs_;
  std::vector<std::vector<std::string>> image_blocks_;
};

}  // namespace imagenets_calibration
