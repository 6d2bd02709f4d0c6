// The calibration's values as messages, for the ports of the calibration blocks
// (friend_calibration/blocks/): MarkerObservation, Sample and Result of calibration.h <->
// imagenets/MarkerObservation, CalibrationSample, CalibrationResult (msg/friend/). Lossless apart
// from rotations, which travel as quaternions (1e-16).
#pragma once

#include <string>

#include <imagenets/CalibrationResult.h>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <imagenets/CalibrationSample.h>
#include <imagenets/MarkerObservation.h>

#include "friend_calibration/calibration.h"

namespace friend_calibration {

// What the robust detection net gave, as the calibration keeps it: found with pose, score, the
// chosen threshold and the points when `detection` found the marker, else not found, `why_not`.
MarkerObservation observationOf(const imagenets::MarkerDetection* detection, const imagenets::FeedbackTrace* trace,
                                const std::string& why_not);
imagenets::MarkerObservation toMsg(const MarkerObservation& observation);
MarkerObservation fromMsg(const imagenets::MarkerObservation& msg);
imagenets::CalibrationSample toMsg(const Sample& sample);
Sample fromMsg(const imagenets::CalibrationSample& msg);
// `base` / `child`: the fixed point's frames.
imagenets::CalibrationResult toMsg(const Result& result, const std::string& base, const std::string& child);
Result fromMsg(const imagenets::CalibrationResult& msg);

}  // namespace friend_calibration
