// What the FRIEND calibration blocks share: the robot model named by a `description` property
// (loaded once per file) and the sample of repetition k, with errors naming property or port.
#pragma once

#include <string>
#include <vector>

#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <std_msgs/Int32.h>

#include "imagenets_calibration/bag_samples.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets/block.h"

namespace imagenets_calibration {
namespace blocks {

// The nominal model of the description file in `path` (required); with `calibration_camera`
// ("stereo" or "mono"; "" the description's own) measuring with that camera. A bad camera throws
// BlockError naming the property.
const RobotModel& robotModel(const std::string& path, const std::string& calibration_camera = "");
// The property `calibration_camera` of the blocks that measure or plan with the calibration camera.
imagenets::PropertySpec calibrationCameraProperty();

// The index this run works on: the input `repetition` (a repeated sub-net's index) when it has a
// value, else the property `index`; checked against the plan's sample count.
int sampleIndex(const imagenets::Context& ctx, const imagenets_calibration_msgs::CalibrationPlan& plan);

// How a bag's samples are found (BagSampleSettings), as properties: declared once here for every
// block that reads them (the plan counts the samples, the bag sample block takes one), so both
// find the same; the calibration sets them on the whole net tree.
std::vector<imagenets::PropertySpec> bagSampleProperties();
BagSampleSettings bagSampleSettings(const imagenets::Context& ctx);

}  // namespace blocks
}  // namespace imagenets_calibration
