// libapriltag (Debian's AprilTag 3) as a second marker detector and as the peer of the square
// marker detector in the marker study. Lens distortion: the detected corners are undistorted and
// the tag homography recomputed from them before libapriltag's own pose estimation
// (estimate_tag_pose: the better of its two solutions; Debian's build exports only that one).
//
// Poses use the marker frame of marker.h (x right, y up, z out of the face); libapriltag's own
// tag frame (y down, z into the tag) is converted.
#pragma once

#include <memory>
#include <string>

#include "imagenets/vision/marker.h"

namespace imagenets {
namespace marker {

struct AprilTagOptions {
  std::string family = "tag36h11";  // tag36h11, tag25h9, tag16h5, tagStandard41h12
  int id = -1;                      // -1: the first tag found (lowest id), else only this id
  double size = 0.060;              // metres, outer edge of the black border (libapriltag's tagsize)
  double quad_decimate = 1.0;       // libapriltag's quad_decimate (1 = full resolution)
  double quad_sigma = 0.0;
  bool refine_edges = true;
  int threads = 1;
};

// Not thread-safe (libapriltag keeps state): one per thread.
class AprilTagDetector {
 public:
  explicit AprilTagDetector(const AprilTagOptions& options);
  ~AprilTagDetector();
  AprilTagDetector(const AprilTagDetector&) = delete;
  AprilTagDetector& operator=(const AprilTagDetector&) = delete;

  const AprilTagOptions& options() const { return options_; }
  // Detection with points 0..3 = outer corners TL TR BR BL (4..7 left at 0), confidence =
  // decision_margin / 100 clamped to [0, 1]. Throws std::invalid_argument for a bad image.
  Detection detect(const cv::Mat& gray, const render::CameraModel& camera) const;

 private:
  struct Impl;
  AprilTagOptions options_;
  std::unique_ptr<Impl> impl_;
};

// The tag as a renderable plane of the same physical layout as markerPlane(): the black-bordered
// code `options.size` wide, plus a white quiet zone of `margin` x size on each side.
render::Plane aprilTagPlane(const AprilTagOptions& options, int id, double margin, const Eigen::Isometry3d& pose,
                            int pixels_per_cell = 120);

}  // namespace marker
}  // namespace imagenets
