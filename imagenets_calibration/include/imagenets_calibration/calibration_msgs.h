// The calibration's values as messages, for the ports of the calibration blocks
// (imagenets_calibration/blocks/): MarkerObservation, Sample and Result of calibration.h <->
// imagenets_calibration_msgs/MarkerObservation, CalibrationSample, CalibrationResult (msg/friend/). Lossless apart
// from rotations, which travel as quaternions (1e-16).
#pragma once

#include <string>

#include <imagenets_calibration_msgs/Calibrate.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <imagenets_calibration_msgs/CalibrationSample.h>
#include <imagenets_calibration_msgs/MarkerObservation.h>

#include "imagenets_calibration/calibration.h"

namespace imagenets_calibration {

// What the robust detection net gave, as the calibration keeps it: found with pose, score, the
// chosen threshold and the points when `detection` found the marker, else not found, `why_not`.
MarkerObservation observationOf(const imagenets::MarkerDetection* detection, const imagenets::FeedbackTrace* trace,
                                const std::string& why_not);
imagenets_calibration_msgs::MarkerObservation toMsg(const MarkerObservation& observation);
MarkerObservation fromMsg(const imagenets_calibration_msgs::MarkerObservation& msg);
imagenets_calibration_msgs::CalibrationSample toMsg(const Sample& sample);
Sample fromMsg(const imagenets_calibration_msgs::CalibrationSample& msg);
// `base` / `child`: the fixed point's frames.
imagenets_calibration_msgs::CalibrationResult toMsg(const Result& result, const std::string& base, const std::string& child);
Result fromMsg(const imagenets_calibration_msgs::CalibrationResult& msg);
// The Calibrate response's summary of a result: its fields taken from the result message's of
// the same meaning (the action's result is the same definition). The fields that depend on the
// run (times, target, files) are left to the caller.
void summarize(const imagenets_calibration_msgs::CalibrationResult& result, imagenets_calibration_msgs::Calibrate::Response& out);

}  // namespace imagenets_calibration
