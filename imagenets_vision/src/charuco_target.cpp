// ChArUco targets (target.h) with OpenCV's aruco module (Debian's libopencv-contrib-dev, OpenCV 4.6:
// the old aruco API): markers found by detectMarkers, the chessboard corners between them by
// interpolateCornersCharuco (sub-pixel), the pose fitted to the corners. The only file that sees
// aruco's headers.
#include <algorithm>
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
  // aruco's corner refinement (OpenCV 4.6, CharucoSubpixelParallel) runs cornerSubPix on the point
  // less (0.5, 0.5) and adds it back: its corners count from a pixel's top-left corner, where the
  // camera model (and cornerSubPix itself) puts pixel centres at integers. Uncorrected, every
  // corner is half a pixel off and a pose 0.29 mm (median, A4 board at 0.6 m) instead of 0.07 mm.
  constexpr double kArucoPixelOrigin = 0.5;
  for (size_t i = 0; i < ids.size(); ++i) {
    out.ids.push_back(ids[i]);
    out.points.emplace_back(corners[i].x - kArucoPixelOrigin, corners[i].y - kArucoPixelOrigin);
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
