// ChArUco targets (target.h) with OpenCV's aruco module (Debian's libopencv-contrib-dev, OpenCV 4.6:
// the old aruco API): markers found by detectMarkers, the chessboard corners between them by
// interpolateCornersCharuco (sub-pixel), the pose fitted to the corners. The only file that sees
// aruco's headers.
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>

#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>

#include "target_internal.h"

namespace imagenets {
namespace target {
namespace detail {

namespace {

const std::vector<std::pair<const char*, cv::aruco::PREDEFINED_DICTIONARY_NAME>>& dictionaries() {
  using namespace cv::aruco;
  static const std::vector<std::pair<const char*, PREDEFINED_DICTIONARY_NAME>> all{
      {"DICT_4X4_50", DICT_4X4_50},       {"DICT_4X4_100", DICT_4X4_100},
      {"DICT_4X4_250", DICT_4X4_250},     {"DICT_4X4_1000", DICT_4X4_1000},
      {"DICT_5X5_50", DICT_5X5_50},       {"DICT_5X5_100", DICT_5X5_100},
      {"DICT_5X5_250", DICT_5X5_250},     {"DICT_5X5_1000", DICT_5X5_1000},
      {"DICT_6X6_50", DICT_6X6_50},       {"DICT_6X6_100", DICT_6X6_100},
      {"DICT_6X6_250", DICT_6X6_250},     {"DICT_6X6_1000", DICT_6X6_1000},
      {"DICT_7X7_50", DICT_7X7_50},       {"DICT_7X7_100", DICT_7X7_100},
      {"DICT_7X7_250", DICT_7X7_250},     {"DICT_7X7_1000", DICT_7X7_1000},
      {"DICT_ARUCO_ORIGINAL", DICT_ARUCO_ORIGINAL},
      {"DICT_APRILTAG_16h5", DICT_APRILTAG_16h5},   {"DICT_APRILTAG_25h9", DICT_APRILTAG_25h9},
      {"DICT_APRILTAG_36h10", DICT_APRILTAG_36h10}, {"DICT_APRILTAG_36h11", DICT_APRILTAG_36h11},
  };
  return all;
}

cv::Ptr<cv::aruco::Dictionary> dictionaryOf(const std::string& name) {
  for (const auto& d : dictionaries()) {
    if (name == d.first) return cv::aruco::getPredefinedDictionary(d.second);
  }
  throw std::invalid_argument("aruco dictionary '" + name + "' is unknown");
}

// One board per target description (OpenCV builds its tables once).
cv::Ptr<cv::aruco::CharucoBoard> boardOf(const TargetDescription& t) {
  static std::mutex mutex;
  static std::map<std::string, cv::Ptr<cv::aruco::CharucoBoard>> boards;
  std::ostringstream key;
  key.precision(17);
  key << t.dictionary << " " << t.squares_x << " " << t.squares_y << " " << t.square_size << " " << t.marker_size;
  std::lock_guard<std::mutex> lock(mutex);
  auto& b = boards[key.str()];
  if (!b) {
    b = cv::aruco::CharucoBoard::create(t.squares_x, t.squares_y, static_cast<float>(t.square_size),
                                        static_cast<float>(t.marker_size), dictionaryOf(t.dictionary));
  }
  return b;
}

// The distance (px) from a chessboard corner to the nearest detected corner of the markers beside it,
// or -1 when none of them was detected.
double distanceToNearestMarker(const cv::aruco::CharucoBoard& board, const std::vector<std::vector<cv::Point2f>>& markers,
                               const std::vector<int>& marker_ids, int corner_id, const cv::Point2f& corner) {
  double nearest = -1;
  for (size_t j = 0; j < board.nearestMarkerIdx[corner_id].size(); ++j) {
    const int id = board.ids[board.nearestMarkerIdx[corner_id][j]];
    const auto it = std::find(marker_ids.begin(), marker_ids.end(), id);
    if (it == marker_ids.end()) continue;
    const cv::Point2f& m = markers[it - marker_ids.begin()][board.nearestMarkerCorners[corner_id][j]];
    const double d = cv::norm(m - corner);
    if (nearest < 0 || d < nearest) nearest = d;
  }
  return nearest;
}

// Refines the chessboard corners again with windows that stay clear of the markers. aruco's own
// refinement (OpenCV 4.6) sizes a corner's window by the distance to the nearest marker corner
// less 2 px, so the square window's sides reach past the white margin into the markers' edges
// whenever the margin is over ~5 px (an upright board: the window's corner points at the marker's):
// the edges pull every corner the same way, 0.14 mm on the calibration's pose. Here the whole
// window, gradients included, stays inside the circle the nearest marker corner leaves free.
// aruco also counts pixels from their top-left corner where the camera model (and cornerSubPix)
// puts pixel centres at integers: its corners are half a pixel off, corrected first.
void refineClearOfMarkers(const cv::Mat& gray, const cv::aruco::CharucoBoard& board,
                          const std::vector<std::vector<cv::Point2f>>& markers, const std::vector<int>& marker_ids,
                          const std::vector<int>& ids, std::vector<cv::Point2f>* corners) {
  constexpr float kArucoPixelOrigin = 0.5f;
  // Half-size. A smaller clear window (margins under ~5 px) is noisier than aruco's pull: the
  // marker study's 15 mm board, median error 0.09 mm with aruco's corners, 0.27 mm with 2.
  constexpr int kSmallestWindow = 4;
  constexpr double kLargestMove = 1.0;  // px; a refinement that moves further has lost the corner
  const cv::TermCriteria stop(cv::TermCriteria::MAX_ITER | cv::TermCriteria::EPS, 100, 0.01);
  for (size_t i = 0; i < ids.size(); ++i) {
    cv::Point2f& c = (*corners)[i];
    c -= cv::Point2f(kArucoPixelOrigin, kArucoPixelOrigin);
    const double free_radius = distanceToNearestMarker(board, markers, marker_ids, ids[i], c);
    // The window's corner, one more pixel for the gradient, inside the free circle.
    const int half = static_cast<int>(std::floor((free_radius - 1.0) / std::sqrt(2.0) - 1.0));
    if (half < kSmallestWindow) continue;
    std::vector<cv::Point2f> refined{c};
    cv::cornerSubPix(gray, refined, cv::Size(half, half), cv::Size(-1, -1), stop);
    if (cv::norm(refined[0] - c) <= kLargestMove) c = refined[0];
  }
}

}  // namespace

bool charucoDictionary(const std::string& name, int* markers, std::string* known) {
  for (const auto& d : dictionaries()) {
    if (name != d.first) continue;
    *markers = cv::aruco::getPredefinedDictionary(d.second)->bytesList.rows;
    return true;
  }
  known->clear();
  for (const auto& d : dictionaries()) *known += (known->empty() ? "" : ", ") + std::string(d.first);
  return false;
}

std::vector<cv::Point3f> charucoCorners(const TargetDescription& t) { return boardOf(t)->chessboardCorners; }

cv::Mat charucoImage(const TargetDescription& t, int width_px, int height_px) {
  cv::Mat image;
  boardOf(t)->draw(cv::Size(width_px, height_px), image, 0, 1);
  return image;
}

TargetDetection detectCharuco(const cv::Mat& gray, const render::CameraModel& camera, const TargetDescription& t,
                              const TargetDetectorOptions& options) {
  const cv::Ptr<cv::aruco::CharucoBoard> board = boardOf(t);
  const cv::Mat K(camera.K), D = camera.D.empty() ? cv::Mat() : cv::Mat(camera.D);
  std::vector<std::vector<cv::Point2f>> marker_corners, rejected;
  std::vector<int> marker_ids;
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  cv::aruco::detectMarkers(gray, board->dictionary, marker_corners, marker_ids, params, rejected);
  // Markers of the board missed at first, looked for again where the board says they are.
  if (!marker_ids.empty()) {
    cv::aruco::refineDetectedMarkers(gray, board, marker_corners, marker_ids, rejected, K, D);
  }
  TargetDetection out;
  // Only this board's markers (a dictionary has more than the board uses).
  std::vector<std::vector<cv::Point2f>> ours;
  std::vector<int> our_ids;
  for (size_t i = 0; i < marker_ids.size(); ++i) {
    if (std::find(board->ids.begin(), board->ids.end(), marker_ids[i]) == board->ids.end()) continue;
    ours.push_back(marker_corners[i]);
    our_ids.push_back(marker_ids[i]);
  }
  out.tags = static_cast<int>(our_ids.size());
  if (our_ids.empty()) {
    out.reason = "no marker of the " + t.dictionary + " board found";
    return out;
  }
  std::vector<cv::Point2f> corners;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(ours, our_ids, gray, board, corners, ids, K, D, std::max(1, options.min_markers));
  const std::map<int, Eigen::Vector3d> object = t.corners();
  refineClearOfMarkers(gray, *board, ours, our_ids, ids, &corners);
  for (size_t i = 0; i < ids.size(); ++i) {
    out.ids.push_back(ids[i]);
    out.points.emplace_back(corners[i].x, corners[i].y);
    out.object_points.push_back(object.at(ids[i]));
  }
  out.confidence = std::min(1.0, static_cast<double>(ids.size()) / std::max<size_t>(1, board->chessboardCorners.size()));
  if (static_cast<int>(ids.size()) < std::max(4, options.min_corners)) {
    out.reason = std::to_string(ids.size()) + " chessboard corners found, fewer than " +
                 std::to_string(std::max(4, options.min_corners));
    return out;
  }
  out.found = fitTargetPose(camera, options, &out);
  if (!out.found) out.reason = "no pose fits the corners (all on one line?)";
  return out;
}

}  // namespace detail
}  // namespace target
}  // namespace imagenets
