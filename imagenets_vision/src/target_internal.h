// What target.cpp shares with apriltag_target.cpp and charuco_target.cpp (not installed): the
// AprilTag families and the ChArUco board, each kept behind plain functions so that libapriltag's
// and OpenCV aruco's headers stay in one file each.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "imagenets/vision/target.h"

namespace imagenets {
namespace target {
namespace detail {

// ---- AprilTag (apriltag_target.cpp) -------------------------------------------------------------
struct FamilyInfo {
  int codes = 0;           // ids 0 .. codes-1
  int border_cells = 0;    // cells across the square libapriltag detects (width_at_border)
  int total_cells = 0;     // cells across the whole code image (with its white / data ring)
  bool reversed_border = false;
};
// False (with the known names in `known`) for a family libapriltag does not have.
bool aprilTagFamily(const std::string& name, FamilyInfo* info, std::string* known);
// The code image of one tag, total_cells square, 0 / 255.
cv::Mat aprilTagCells(const std::string& family, int id);
TargetDetection detectAprilTags(const cv::Mat& gray, const render::CameraModel& camera, const TargetDescription& t,
                                const TargetDetectorOptions& options);

// ---- ChArUco (charuco_target.cpp) ---------------------------------------------------------------
// False (with the known names) for a dictionary OpenCV does not have; `markers`: its size.
bool charucoDictionary(const std::string& name, int* markers, std::string* known);
// Chessboard corners by id in OpenCV's board frame (OpenCV 4.6: origin at the top left of its
// drawing, x right, y down).
std::vector<cv::Point3f> charucoCorners(const TargetDescription& t);
// The board drawn by OpenCV, width x height pixels (no margin), 0 / 255.
cv::Mat charucoImage(const TargetDescription& t, int width_px, int height_px);
TargetDetection detectCharuco(const cv::Mat& gray, const render::CameraModel& camera, const TargetDescription& t,
                              const TargetDetectorOptions& options);

}  // namespace detail
}  // namespace target
}  // namespace imagenets
