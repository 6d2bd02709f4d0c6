// Calibration targets people print, described by a small YAML file (config/targets/), and their
// detection as corners with ids:
//
//   type: square_marker   marker: ../markers/gripper.yaml    the paper's square marker (marker.h)
//   type: apriltag        family: tag36h11, id: 0, size: 0.06 [rows: R, cols: C, spacing: S] [margin: M]
//   type: charuco         dictionary: DICT_5X5_100, squares_x: 5, squares_y: 7, square_size: 0.03,
//                         marker_size: 0.022 [first_id: 0] [width: W, height: H] [margin: M]
//
// Every target has one frame, the one of marker.h and render.h: origin at the centre of the
// printed pattern, x right, y up (towards the top of the print), z out of the printed face. A
// target mounted where the robot description puts its marker is therefore seen by the calibration
// exactly as the square marker would be.
//
// Corner ids (what a detection reports next to each point, and where the point lies on the print):
//   square_marker  0..7: the 8 defined points of marker.h (outer TL TR BR BL, then inner)
//   apriltag       4 * tag id + k, k = 0..3 the corners TL TR BR BL of that tag's black square
//   charuco        OpenCV's chessboard corner ids: 0 at the top left, along x first, then the rows below
// A grid of tags is Kalibr's AprilGrid layout: `rows` x `cols` tags with ids from `id` upwards, left
// to right along the bottom row first, then the rows above; `spacing` is the white gap between
// neighbouring black squares (metres).
//
// OpenCV's aruco module stays inside target.cpp / charuco_target.cpp: this header is plain.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "imagenets/vision/marker.h"
#include "imagenets/vision/render.h"

namespace imagenets {
namespace target {

// A bad target file: the message names the file and the key ("FILE: 'family': ...").
struct TargetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class TargetType { SquareMarker, AprilTag, Charuco };

struct TargetDescription {
  TargetType type = TargetType::SquareMarker;
  std::string file;  // the YAML it came from (for messages)
  std::string name;  // `name`, else the file's stem

  // square_marker
  std::string marker_file;
  std::shared_ptr<const marker::MarkerDescription> marker;

  // apriltag: one tag (rows = cols = 1) or a grid
  std::string family;   // tag36h11, tag36h10, tag25h9, tag16h5, tagCircle21h7, tagCircle49h12,
                        // tagCustom48h12, tagStandard41h12, tagStandard52h13
  int id = 0;           // the tag's id; a grid: its first (bottom-left) id
  double size = 0;      // edge of a tag's black square, metres (libapriltag's tagsize)
  int rows = 1, cols = 1;
  double spacing = 0;   // gap between neighbouring tags' black squares, metres
  int tag_cells = 0;    // cells across the black square (the family's width_at_border)
  int family_codes = 0; // ids the family has

  // charuco (OpenCV's CharucoBoard)
  std::string dictionary;  // DICT_4X4_50 ... DICT_7X7_1000, DICT_ARUCO_ORIGINAL, DICT_APRILTAG_36h11 ...
  int squares_x = 0, squares_y = 0;
  double square_size = 0, marker_size = 0;  // metres

  // White quiet zone around the pattern, metres (printing, rendering).
  double margin = 0;

  // Loads and checks a target file; throws TargetError naming the file and the key: an unknown
  // key or type, a missing or malformed value, an unknown family or dictionary, a tag id out of the
  // family's range, a board whose markers do not fit its squares (or its squares its width).
  static TargetDescription load(const std::string& yaml_path);
  // The same, loaded once per path and process.
  static std::shared_ptr<const TargetDescription> loadCached(const std::string& yaml_path);

  std::string typeName() const;  // square_marker, apriltag, charuco
  // The pattern's extent on the print without the margin (metres, along x and y).
  double patternWidth() const;
  double patternHeight() const;
  // Every corner id the target has, with its point in the target frame (z = 0).
  std::map<int, Eigen::Vector3d> corners() const;
  // Tag ids of an AprilTag target, bottom-left first.
  std::vector<int> tagIds() const;
  // The centre of tag `index` (0 .. rows * cols - 1, the order of tagIds()) in the target frame.
  Eigen::Vector3d tagCentre(int index) const;

  // The print: the pattern with its margin, `pixels_per_metre` resolution, mono8, dark on white.
  cv::Mat texture(double pixels_per_metre) const;
  // The target as a plane for the renderer at `pose` (T_camera_target), its texture scaled so that
  // the printed geometry is where corners() says (ground truth must be exact).
  render::Plane plane(const Eigen::Isometry3d& pose, double pixels_per_metre = 16000.0) const;
};

// A detection: the corners found with their ids and their points on the target, and the target's
// pose fitted to all of them (IPPE + Levenberg-Marquardt through the camera model, both solutions).
struct TargetDetection {
  bool found = false;
  double confidence = 0;  // apriltag: mean decision margin / 100; charuco: corners found / all; clamped to [0, 1]
  std::vector<int> ids;
  std::vector<cv::Point2d> points;              // distorted pixels
  std::vector<Eigen::Vector3d> object_points;   // in the target frame
  int tags = 0;  // tags / board markers seen
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();      // T_camera_target
  Eigen::Isometry3d alt_pose = Eigen::Isometry3d::Identity();  // the other planar solution
  double reprojection_error = 0, alt_reprojection_error = 0;   // RMS px
  std::string reason;  // why not found
};

struct TargetDetectorOptions {
  // libapriltag
  double quad_decimate = 1.0;
  double quad_sigma = 0.0;
  int threads = 1;
  // The tags' black squares are located again on the gray image by the square marker's edge fit
  // (marker.h: the crossings of the mid-level along each edge, lines fitted after undistortion),
  // which is far more accurate than libapriltag's corners; a tag whose edges cannot be located keeps them.
  bool refine_edges = true;
  // charuco: corners need this many board markers near them (OpenCV's minMarkers).
  int min_markers = 2;
  // Fewer corners than this: not found (4 at least: the planar pose needs them).
  int min_corners = 4;
  // As marker::DetectorOptions: when both planar solutions fit about equally, the one closer to the hint.
  const Eigen::Isometry3d* pose_hint = nullptr;
  double ambiguity_ratio = 1.5;
};

// Detects an apriltag or charuco target in a mono8 image of the camera's size (a square marker
// needs a threshold: marker::detect, or the robust detection nets). Throws std::invalid_argument
// for a bad image or a square_marker target.
TargetDetection detectTarget(const cv::Mat& gray, const render::CameraModel& camera, const TargetDescription& target,
                             const TargetDetectorOptions& options = TargetDetectorOptions());

// The target pose from corners (distorted pixels, points in the target frame): IPPE's two planar
// solutions, each refined by Levenberg-Marquardt through the camera model; fills pose, alt_pose and
// their RMS errors in `d`. False with fewer than 4 points or when no solution is found.
bool fitTargetPose(const render::CameraModel& camera, const TargetDetectorOptions& options, TargetDetection* d);

// A square marker detection (marker.h) as a target detection: ids 0..7 and the marker's points.
TargetDetection fromMarkerDetection(const marker::Detection& d, const marker::MarkerDescription& marker);

}  // namespace target
}  // namespace imagenets
