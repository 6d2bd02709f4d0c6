// Square (ARToolKit-style) markers: the description file, the printable / renderable texture and
// the detector (paper 3.4, Fig. 3.3). The detector is a plain function so the block, the command
// line tool, the study and the benchmarks share it.
//
// Marker frame (same as render.h): origin at the marker centre, x right, y up (towards the top
// of the pattern image), z out of the printed face. The 8 defined points, in this order:
//   0..3  outer corners of the black border: top-left, top-right, bottom-right, bottom-left
//   4..7  inner corners of the border (corners of the pattern area), same order
// A front-facing marker shows them clockwise in the image.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "imagenets/vision/render.h"

namespace imagenets {
namespace marker {

struct MarkerDescription {
  std::string name;
  std::string file;         // the YAML it came from (for messages)
  double size = 0.06;       // outer edge of the black border, metres
  double border = 0.25;     // border width / size
  double margin = 0.25;     // white quiet zone / size (printing and rendering only)
  cv::Mat pattern;          // CV_8UC1, the inner area, dark on white

  // Loads `config/markers/<name>.yaml` (pattern path relative to the YAML). Throws
  // std::runtime_error naming the file and the key for a missing / bad field or pattern image.
  static MarkerDescription load(const std::string& yaml_path);
  // The same, loaded once per path and process (blocks ask for it on every run).
  static std::shared_ptr<const MarkerDescription> loadCached(const std::string& yaml_path);

  double innerSize() const { return size * (1.0 - 2.0 * border); }
  // The 8 defined points in the marker frame (z = 0), in the order above.
  std::vector<cv::Point3d> definedPoints() const;
  // The marker as an image: the black border and the pattern, with the white margin around it if
  // `with_margin`; `pixels_per_metre` sets the resolution. Physical width: size (+ 2 margins).
  cv::Mat texture(double pixels_per_metre, bool with_margin = true) const;
  double textureWidth(bool with_margin = true) const { return size * (1.0 + (with_margin ? 2.0 * margin : 0.0)); }
};

// The marker (with its white margin) as a plane for the renderer, at `pose` (T_camera_marker).
// `pixels_per_metre` of the texture: ~4x the expected image resolution keeps it sharp.
render::Plane markerPlane(const MarkerDescription& marker, const Eigen::Isometry3d& pose,
                          double pixels_per_metre = 16000.0);

struct DetectorOptions {
  double min_confidence = 0.5;  // below: found = false
  double min_side_px = 12.0;    // quads with a shorter side (contour or located square) are ignored
  int refine_passes = 2;        // sub-pixel edge refinement passes on the gray image (0 = none)
  // The dark regions' outlines traced on every `decimate`-th pixel and row of the thresholded
  // image (1: all). Tracing is most of a threshold trial's cost on a noisy image (thousands of
  // specks); the rough corners it gives are then located on the full gray image as before, so a
  // marker whose border is a few pixels wide at that scale is found at the same corners. With a
  // pose hint that shows the border under 3 px at that scale (far, steep), every pixel is traced.
  int decimate = 1;
  // After the refinement, fit a blurred-step model to every pixel along each outer edge (more
  // accurate in dim, noisy, blurred images, where single profile crossings are noisy).
  bool edge_model = false;
  // The edge model only for markers whose every side is shorter than this (pixels; 0: any size).
  // Short edges give the profile refinement few, noisy crossings; long ones enough, and a profile
  // fit shrugs off a reflection across part of an edge, which pulls the edge model's band.
  double edge_model_max_side_px = 0;
  int pattern_cells = 32;       // resolution of the rectified pattern compared with the marker's
  // Image blurs (Gaussian sigma, pixels) under which a candidate the sharp pattern rejects is
  // matched again: against the pattern rendered through the candidate's homography and blurred so.
  // Small, far, blurred markers, whose cells smear into each other; empty: the sharp match only.
  std::vector<double> match_blur_px;
  // Weight of the 4 inner corners in the pose fit relative to the outer ones. 2 (the ratio of
  // their distances from the centre) cancels a common shift of every edge towards the dark side,
  // as over-exposure (clipped white) causes: the outer square shrinks, the inner one grows.
  int inner_weight = 2;
  // The inner corners take part in the pose fit only when every side of the inner square is at
  // least this long in the image (pixels) and their edges were located; 0: always.
  double min_inner_side_px = 0;
  // Optional pose hint (e.g. the previous frame's pose): when both IPPE solutions fit the points
  // about equally well (error ratio < ambiguity_ratio), the one closer to the hint is taken.
  const Eigen::Isometry3d* pose_hint = nullptr;
  // With a pose hint: quadrilaterals whose shortest side is under this share of the hinted
  // marker's shortest side (in the image) are not examined (0: all). The hint's scale is known to
  // within tens of percent, so 0.5 loses no marker and skips the specks and far-off squares that
  // are most of the candidates in a cluttered region.
  double min_side_of_hint = 0;
  double ambiguity_ratio = 1.5;
};

struct Detection {
  bool found = false;
  double confidence = 0.0;          // best zero-mean normalised correlation of the rectified
                                    // inner area with the pattern over 4 rotations, clamped to [0,1]
  std::array<cv::Point2d, 8> points;  // the 8 defined points, distorted pixel coordinates
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();      // T_camera_marker (chosen)
  Eigen::Isometry3d alt_pose = Eigen::Isometry3d::Identity();  // the other IPPE solution
  double reprojection_error = 0.0;  // RMS, pixels, chosen solution
  double alt_reprojection_error = 0.0;
  int rotation = 0;                 // quarter turns that aligned the pattern
  int candidates = 0;               // quadrilaterals examined
};

// Finds the marker. `binary`: thresholded image (marker border dark = 0); `gray`: the 8-bit gray
// image the corners are refined on; both CV_8UC1 of the camera's size. Throws std::invalid_argument
// for inputs of the wrong type or size.
Detection detect(const cv::Mat& gray, const cv::Mat& binary, const render::CameraModel& camera,
                 const MarkerDescription& marker, const DetectorOptions& options = DetectorOptions());

// Locates the 4 edges of a dark square on a bright surround (a square marker's or an AprilTag's
// black border) on the gray image, as detect() does: mid-level crossings along each edge,
// undistorted, a line fitted to each, corners intersected; `passes` times. `quad_px`: rough corners
// (distorted pixels, in order around the square). False if an edge could not be located.
bool refineSquareEdges(const cv::Mat& gray, const render::CameraModel& camera, const std::vector<cv::Point2d>& quad_px,
                       int passes, std::vector<cv::Point2d>* refined_px);

// Angle (radians) of the rotation between two poses and the distance between their origins.
double rotationAngle(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace marker
}  // namespace imagenets
