// Calibration files (YAML): the fixed point, its spread, and every raw sample (joint states and
// both detections) so a calibration can be re-solved later without the robot (replay).
// Written atomically (temporary file + rename); the previous file is kept beside it with its
// time stamp (pth_fixed_point.20261122T041500Z.yaml). The last line is the CRC-32 of all before it
// (`crc32: 0x1a2b3c4d`), so a file cut short or altered is refused when read.
#pragma once

#include <string>

#include "imagenets_calibration/calibration.h"

namespace imagenets_calibration {

struct StoredCalibration {
  std::string file;
  std::string base_frame = "base_link";
  std::string child_frame = "pth_fixed_point";
  std::string created;  // UTC, ISO 8601
  Result result;
};

// Writes `calibration` to `path` (creating its directory). Returns the path the previous file was
// archived to ("" when there was none). Throws std::runtime_error naming the path on failure; the
// old file is then untouched.
std::string saveCalibration(const StoredCalibration& calibration, const std::string& path);
// Throws std::runtime_error naming the file (and the key) on a missing, empty, incomplete (no CRC
// line at its end), corrupt (CRC differs) file or bad content.
StoredCalibration loadCalibration(const std::string& path);
// Why `fresh` must not replace the calibration saved at `path` ("" = it may): the saved one is
// good (readable, and its 3-sigma translation bound within `max_uncertainty` when it has one) and
// the fresh one's 3-sigma translation bound (3 sqrt(trace), m) is above `max_uncertainty`.
// `max_uncertainty` <= 0: never refuses; a fresh result without covariance (paper method) is not
// judged.
std::string overwriteRefusal(const Result& fresh, const std::string& path, double max_uncertainty);
// The calibrated URDF (as Fetch's robot_calibration writes one): the nominal robot's URDF with the
// calibration applied (calibratedModel; robot_description/urdf_writer.h): the robot's own URDF
// when its description has one (config/six_axis: links and joints keep their names), else the
// URDF generated from the description. The head mount joint's origin is the fixed point, the
// marker joint's origin the estimated marker offset, and each estimated joint zero offset is folded
// into its revolute joint's origin (a rotation about the joint axis). robot_state_publisher and KDL
// ignore URDF <calibration> elements, so offsets written there would not take effect; a comment at
// the top lists the changes. The robot's joint_states (raw encoder readings) then give the
// calibrated TF.
std::string calibratedUrdf(const RobotModel& nominal, const StoredCalibration& calibration);
// Writes calibratedUrdf atomically to `path` (creating its directory). Throws std::runtime_error
// naming the path on failure; the previous file is then untouched.
void saveCalibratedUrdf(const RobotModel& nominal, const StoredCalibration& calibration, const std::string& path);
// Where the calibrated URDF of a calibration file goes: beside it, .urdf instead of the extension
// (pth_fixed_point.yaml -> pth_fixed_point.urdf).
std::string urdfFileBeside(const std::string& calibration_file);
// Current UTC time as 20261122T041500Z (file names) or 2026-11-22T04:15:00Z (iso = true).
std::string utcStamp(bool iso);

}  // namespace imagenets_calibration
