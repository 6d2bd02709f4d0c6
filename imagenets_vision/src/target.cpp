// Target files, their geometry and print, and the pose from corners (see target.h).
#include "imagenets/vision/target.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <boost/filesystem.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/yaml.h>

#include "target_internal.h"

namespace imagenets {
namespace target {

namespace {

// Reads the keys of one target file; every message names the file and the key.
class Keys {
 public:
  Keys(const YAML::Node& root, const std::string& file) : root_(root), file_(file) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw TargetError(file_ + ": '" + key + "': " + what);
  }
  bool has(const std::string& key) const { return static_cast<bool>(root_[key]); }
  std::string text(const std::string& key, const std::string* fallback = nullptr) {
    used_.insert(key);
    const YAML::Node n = root_[key];
    if (!n) {
      if (fallback) return *fallback;
      fail(key, "missing (required for type '" + type_ + "')");
    }
    if (!n.IsScalar() || n.Scalar().empty()) fail(key, "must be text");
    return n.Scalar();
  }
  double number(const std::string& key, double lo, double hi, const double* fallback = nullptr) {
    used_.insert(key);
    const YAML::Node n = root_[key];
    if (!n) {
      if (fallback) return *fallback;
      fail(key, "missing (required for type '" + type_ + "')");
    }
    double v;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "'" + (n.IsScalar() ? n.Scalar() : std::string("(not a scalar)")) + "' is not a number");
    }
    if (!(v > lo && v <= hi)) {
      std::ostringstream os;
      os << v << " is out of range (" << lo << ", " << hi << "]";
      fail(key, os.str());
    }
    return v;
  }
  int integer(const std::string& key, int lo, int hi, const int* fallback = nullptr) {
    used_.insert(key);
    const YAML::Node n = root_[key];
    if (!n) {
      if (fallback) return *fallback;
      fail(key, "missing (required for type '" + type_ + "')");
    }
    long v;
    try {
      const std::string s = n.Scalar();
      size_t end = 0;
      v = std::stol(s, &end);
      if (end != s.size()) throw std::invalid_argument(s);
    } catch (const std::exception&) {
      fail(key, "'" + (n.IsScalar() ? n.Scalar() : std::string("(not a scalar)")) + "' is not an integer");
    }
    if (v < lo || v > hi) fail(key, std::to_string(v) + " is out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(v);
  }
  void setType(const std::string& type) { type_ = type; }
  // Every key not read is unknown for this type.
  void rejectUnknown() const {
    for (const auto& kv : root_) {
      const std::string key = kv.first.as<std::string>();
      if (used_.count(key)) continue;
      std::string known;
      for (const auto& k : used_) known += (known.empty() ? "" : ", ") + k;
      fail(key, "unknown key for type '" + type_ + "' (known: " + known + ")");
    }
  }

 private:
  const YAML::Node root_;
  const std::string file_;
  std::string type_;
  std::set<std::string> used_;
};

const char* kTypes = "square_marker, apriltag, charuco";

}  // namespace

namespace {

// The keys of each target type (the file's `type`), into `t`; Keys names the file and key of a bad value.
void loadSquareMarker(Keys& keys, const std::string& yaml_path, TargetDescription& t) {
  const boost::filesystem::path marker = keys.text("marker");
  t.marker_file = (marker.is_absolute() ? marker : boost::filesystem::absolute(yaml_path).parent_path() / marker)
                      .lexically_normal()
                      .string();
  try {
    t.marker = marker::MarkerDescription::loadCached(t.marker_file);
  } catch (const std::exception& e) {
    keys.fail("marker", e.what());
  }
  t.size = t.marker->size;
  t.margin = t.marker->margin * t.marker->size;
}

void loadAprilTag(Keys& keys, TargetDescription& t) {
  t.family = keys.text("family");
  detail::FamilyInfo info;
  std::string known;
  if (!detail::aprilTagFamily(t.family, &info, &known)) keys.fail("family", "'" + t.family + "' is not an AprilTag family libapriltag has (" + known + ")");
  t.tag_cells = info.border_cells;
  t.family_codes = info.codes;
  t.size = keys.number("size", 0.0, 10.0);
  const int one = 1;
  t.rows = keys.integer("rows", 1, 100, &one);
  t.cols = keys.integer("cols", 1, 100, &one);
  t.id = keys.integer("id", 0, 1 << 30);
  const int last = t.id + t.rows * t.cols - 1;
  if (last >= info.codes) {
    keys.fail("id", (t.rows * t.cols > 1 ? "the grid's ids " + std::to_string(t.id) + ".." + std::to_string(last)
                                         : std::to_string(t.id)) +
                        " out of range: family " + t.family + " has ids 0.." + std::to_string(info.codes - 1));
  }
  const double cell = t.size / info.border_cells;
  // libapriltag needs the ring around each detected square (white, or the data bits of the
  // families whose border is inside): neighbours and the margin must leave room for it.
  const double ring = 0.5 * (info.total_cells - info.border_cells) * cell;
  if (t.rows * t.cols > 1) {
    t.spacing = keys.number("spacing", 0.0, 10.0);
    if (t.spacing < 2 * ring - 1e-12) {
      std::ostringstream os;
      os << t.spacing << " m leaves no room for the tags' " << info.total_cells - info.border_cells
         << " cells around their squares (at least " << 2 * ring << " m for " << t.family << " of size " << t.size << ")";
      keys.fail("spacing", os.str());
    }
  } else if (keys.has("spacing")) {
    keys.number("spacing", -1.0, 10.0);  // harmless on one tag
  }
  const double default_margin = std::max(ring + cell, 0.25 * t.size);
  t.margin = keys.number("margin", -1e-12, 10.0, &default_margin);
  if (t.margin < ring - 1e-12) {
    std::ostringstream os;
    os << t.margin << " m is narrower than the ring libapriltag needs around the squares (" << ring << " m)";
    keys.fail("margin", os.str());
  }
}

void loadCharuco(Keys& keys, TargetDescription& t) {
  t.dictionary = keys.text("dictionary");
  int markers = 0;
  std::string known;
  if (!detail::charucoDictionary(t.dictionary, &markers, &known)) {
    keys.fail("dictionary", "'" + t.dictionary + "' is not an OpenCV aruco dictionary (" + known + ")");
  }
  t.squares_x = keys.integer("squares_x", 2, 1000);
  t.squares_y = keys.integer("squares_y", 2, 1000);
  t.square_size = keys.number("square_size", 0.0, 10.0);
  t.marker_size = keys.number("marker_size", 0.0, 10.0);
  if (t.marker_size >= t.square_size) {
    std::ostringstream os;
    os << t.marker_size << " m does not fit in its square of " << t.square_size << " m";
    keys.fail("marker_size", os.str());
  }
  const int needed = t.squares_x * t.squares_y / 2;
  if (needed > markers) {
    keys.fail("dictionary", t.dictionary + " has " + std::to_string(markers) + " markers, the " +
                                std::to_string(t.squares_x) + " x " + std::to_string(t.squares_y) + " board needs " +
                                std::to_string(needed));
  }
  // The printed board's size, when given, must hold the squares.
  for (const char* key : {"width", "height"}) {
    if (!keys.has(key)) continue;
    const double v = keys.number(key, 0.0, 100.0);
    const int n = std::string(key) == "width" ? t.squares_x : t.squares_y;
    if (n * t.square_size > v + 1e-9) {
      std::ostringstream os;
      os << v << " m is smaller than its " << n << " squares of " << t.square_size << " m (" << n * t.square_size << " m)";
      keys.fail(key, os.str());
    }
  }
  const double default_margin = 0.5 * t.square_size;
  t.margin = keys.number("margin", -1e-12, 10.0, &default_margin);
  t.size = t.square_size;
}

}  // namespace

TargetDescription TargetDescription::load(const std::string& yaml_path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::BadFile&) {
    throw TargetError(yaml_path + ": cannot read target file");
  } catch (const YAML::Exception& e) {
    throw TargetError(yaml_path + ": not valid YAML: " + e.what());
  }
  if (!root.IsMap()) throw TargetError(yaml_path + ": a target file is a YAML map (type: " + std::string(kTypes) + ")");
  Keys keys(root, yaml_path);
  TargetDescription t;
  t.file = yaml_path;
  const std::string type = keys.text("type");
  keys.setType(type);
  const std::string stem = boost::filesystem::path(yaml_path).stem().string();
  t.name = keys.text("name", &stem);
  if (type == "square_marker") {
    t.type = TargetType::SquareMarker;
    loadSquareMarker(keys, yaml_path, t);
  } else if (type == "apriltag") {
    t.type = TargetType::AprilTag;
    loadAprilTag(keys, t);
  } else if (type == "charuco") {
    t.type = TargetType::Charuco;
    loadCharuco(keys, t);
  } else {
    keys.fail("type", "'" + type + "' is not a target type (" + kTypes + ")");
  }
  keys.rejectUnknown();
  return t;
}

std::shared_ptr<const TargetDescription> TargetDescription::loadCached(const std::string& yaml_path) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const TargetDescription>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[yaml_path];
  if (!entry) entry = std::make_shared<const TargetDescription>(load(yaml_path));
  return entry;
}

std::string TargetDescription::typeName() const {
  switch (type) {
    case TargetType::SquareMarker: return "square_marker";
    case TargetType::AprilTag: return "apriltag";
    case TargetType::Charuco: return "charuco";
  }
  return "";
}

double TargetDescription::patternWidth() const {
  switch (type) {
    case TargetType::SquareMarker: return size;
    case TargetType::AprilTag: return cols * size + (cols - 1) * spacing;
    case TargetType::Charuco: return squares_x * square_size;
  }
  return 0;
}

double TargetDescription::patternHeight() const {
  switch (type) {
    case TargetType::SquareMarker: return size;
    case TargetType::AprilTag: return rows * size + (rows - 1) * spacing;
    case TargetType::Charuco: return squares_y * square_size;
  }
  return 0;
}

std::vector<int> TargetDescription::tagIds() const {
  std::vector<int> ids;
  if (type != TargetType::AprilTag) return ids;
  for (int k = 0; k < rows * cols; ++k) ids.push_back(id + k);
  return ids;
}

Eigen::Vector3d TargetDescription::tagCentre(int index) const {
  const int r = index / cols, c = index % cols;
  const double pitch = size + spacing;
  return {(c - 0.5 * (cols - 1)) * pitch, (r - 0.5 * (rows - 1)) * pitch, 0.0};
}

std::map<int, Eigen::Vector3d> TargetDescription::corners() const {
  std::map<int, Eigen::Vector3d> out;
  if (type == TargetType::SquareMarker) {
    const auto pts = marker->definedPoints();
    for (size_t i = 0; i < pts.size(); ++i) out[static_cast<int>(i)] = Eigen::Vector3d(pts[i].x, pts[i].y, 0);
  } else if (type == TargetType::AprilTag) {
    const double h = size / 2;
    const std::vector<Eigen::Vector3d> offsets{{-h, h, 0}, {h, h, 0}, {h, -h, 0}, {-h, -h, 0}};
    for (int k = 0; k < rows * cols; ++k) {
      for (int j = 0; j < 4; ++j) out[4 * (id + k) + j] = tagCentre(k) + offsets[j];
    }
  } else {
    // OpenCV's board frame has y down (its drawing's rows), ours y up.
    const std::vector<cv::Point3f> pts = detail::charucoCorners(*this);
    const double cx = 0.5 * patternWidth(), cy = 0.5 * patternHeight();
    for (size_t i = 0; i < pts.size(); ++i) out[static_cast<int>(i)] = Eigen::Vector3d(pts[i].x - cx, cy - pts[i].y, 0);
  }
  return out;
}

namespace {

// The print at a resolution where the pattern's unit (a tag cell, a board square) is a whole
// number of texels, so that its edges lie exactly where corners() says; `*ppm` is that resolution.
cv::Mat printTexture(const TargetDescription& t, double pixels_per_metre, double* ppm) {
  if (t.type == TargetType::SquareMarker) {
    *ppm = pixels_per_metre;
    return t.marker->texture(pixels_per_metre, true);
  }
  if (t.type == TargetType::Charuco) {
    const int square_px = std::max(8, static_cast<int>(std::lround(t.square_size * pixels_per_metre)));
    *ppm = square_px / t.square_size;
    const cv::Mat board = detail::charucoImage(t, t.squares_x * square_px, t.squares_y * square_px);
    const int margin_px = static_cast<int>(std::lround(t.margin * *ppm));
    cv::Mat out;
    cv::copyMakeBorder(board, out, margin_px, margin_px, margin_px, margin_px, cv::BORDER_CONSTANT, cv::Scalar(255));
    return out;
  }
  detail::FamilyInfo info;
  std::string known;
  detail::aprilTagFamily(t.family, &info, &known);
  const double cell = t.size / info.border_cells;
  const int cell_px = std::max(2, static_cast<int>(std::lround(cell * pixels_per_metre)));
  *ppm = cell_px / cell;
  // Whole texels: the squares exactly, the gaps and the margin to half a texel.
  const int square_px = info.border_cells * cell_px;
  const int gap_px = static_cast<int>(std::lround(t.spacing * *ppm));
  const int margin_px = static_cast<int>(std::lround(t.margin * *ppm));
  const int width = 2 * margin_px + t.cols * square_px + (t.cols - 1) * gap_px;
  const int height = 2 * margin_px + t.rows * square_px + (t.rows - 1) * gap_px;
  cv::Mat tex(height, width, CV_8UC1, cv::Scalar(255));
  const int ring_px = (info.total_cells - info.border_cells) / 2 * cell_px;
  const std::vector<int> ids = t.tagIds();
  for (size_t k = 0; k < ids.size(); ++k) {
    const cv::Mat cells = detail::aprilTagCells(t.family, ids[k]);
    const int r = static_cast<int>(k) / t.cols, c = static_cast<int>(k) % t.cols;
    // The code image's top-left corner in texels (rows down from the top: the bottom row of tags last).
    const int u0 = margin_px + c * (square_px + gap_px) - ring_px;
    const int v0 = margin_px + (t.rows - 1 - r) * (square_px + gap_px) - ring_px;
    cv::Mat big;
    cv::resize(cells, big, cv::Size(cells.cols * cell_px, cells.rows * cell_px), 0, 0, cv::INTER_NEAREST);
    const cv::Rect where(u0, v0, big.cols, big.rows);
    const cv::Rect inside = where & cv::Rect(0, 0, width, height);
    big(cv::Rect(inside.x - u0, inside.y - v0, inside.width, inside.height)).copyTo(tex(inside));
  }
  return tex;
}

}  // namespace

cv::Mat TargetDescription::texture(double pixels_per_metre) const {
  double ppm;
  return printTexture(*this, pixels_per_metre, &ppm);
}

render::Plane TargetDescription::plane(const Eigen::Isometry3d& pose, double pixels_per_metre) const {
  if (type == TargetType::SquareMarker) return marker::markerPlane(*marker, pose, pixels_per_metre);
  render::Plane p;
  double ppm;
  p.texture = printTexture(*this, pixels_per_metre, &ppm);
  p.width = p.texture.cols / ppm;
  p.height = p.texture.rows / ppm;
  p.pose = pose;
  return p;
}

// ---------------------------------------------------------------- detection

namespace {

Eigen::Isometry3d toIsometry(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = R(r, c);
    T.translation()(r) = tvec.at<double>(r);
  }
  return T;
}

}  // namespace

bool fitTargetPose(const render::CameraModel& camera, const TargetDetectorOptions& options, TargetDetection* d) {
  const size_t n = d->points.size();
  if (n < 4 || d->object_points.size() != n) return false;
  // Points on one line fix no plane (e.g. one row of a board's corners).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : d->object_points) mean += p.head<2>() / static_cast<double>(n);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& p : d->object_points) scatter += (p.head<2>() - mean) * (p.head<2>() - mean).transpose() / static_cast<double>(n);
  const Eigen::Vector2d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvalues();
  if (!(spread[0] > 1e-6 * spread[1]) || !(spread[1] > 0)) return false;
  std::vector<cv::Point3d> object;
  for (const auto& p : d->object_points) object.emplace_back(p.x(), p.y(), p.z());
  const cv::Mat K(camera.K), D = camera.D.empty() ? cv::Mat() : cv::Mat(camera.D);
  std::vector<cv::Mat> rvecs, tvecs;
  int solutions = 0;
  try {
    solutions = cv::solvePnPGeneric(object, d->points, K, D, rvecs, tvecs, false, cv::SOLVEPNP_IPPE);
  } catch (const cv::Exception&) {
    return false;  // degenerate (collinear) points
  }
  if (solutions == 0) return false;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<double> errors;
  for (int s = 0; s < solutions; ++s) {
    cv::Mat rvec = rvecs[s].clone(), tvec = tvecs[s].clone();
    rvec.convertTo(rvec, CV_64F);
    tvec.convertTo(tvec, CV_64F);
    cv::solvePnPRefineLM(object, d->points, K, D, rvec, tvec,
                         cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-12));
    std::vector<cv::Point2d> reprojected;
    cv::projectPoints(object, rvec, tvec, K, D, reprojected);
    double sq = 0;
    for (size_t i = 0; i < n; ++i) {
      const cv::Point2d e = reprojected[i] - d->points[i];
      sq += e.dot(e);
    }
    poses.push_back(toIsometry(rvec, tvec));
    errors.push_back(std::sqrt(sq / n));
  }
  int chosen = 0;
  if (solutions > 1) {
    chosen = errors[1] < errors[0] ? 1 : 0;
    const double lo = std::min(errors[0], errors[1]), hi = std::max(errors[0], errors[1]);
    if (options.pose_hint && hi < options.ambiguity_ratio * std::max(lo, 1e-9)) {
      chosen = marker::rotationAngle(poses[0], *options.pose_hint) <= marker::rotationAngle(poses[1], *options.pose_hint) ? 0 : 1;
    }
  }
  d->pose = poses[chosen];
  d->reprojection_error = errors[chosen];
  d->alt_pose = solutions > 1 ? poses[1 - chosen] : poses[chosen];
  d->alt_reprojection_error = solutions > 1 ? errors[1 - chosen] : errors[chosen];
  return true;
}

TargetDetection detectTarget(const cv::Mat& gray, const render::CameraModel& camera, const TargetDescription& target,
                             const TargetDetectorOptions& options) {
  if (gray.empty() || gray.type() != CV_8UC1) throw std::invalid_argument("gray image must be a non-empty mono8 image");
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw std::invalid_argument("image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                                " but camera_info says " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
  }
  switch (target.type) {
    case TargetType::AprilTag: return detail::detectAprilTags(gray, camera, target, options);
    case TargetType::Charuco: return detail::detectCharuco(gray, camera, target, options);
    case TargetType::SquareMarker: break;
  }
  throw std::invalid_argument(target.file + ": a square marker is found with a threshold (imagenets/SquareMarkerDetector, "
                              "the robust marker detection nets), not by detectTarget");
}

TargetDetection fromMarkerDetection(const marker::Detection& d, const marker::MarkerDescription& marker) {
  TargetDetection t;
  t.found = d.found;
  t.confidence = d.confidence;
  if (!d.found) {
    t.reason = "marker not found";
    return t;
  }
  const auto defined = marker.definedPoints();
  for (size_t i = 0; i < d.points.size(); ++i) {
    t.ids.push_back(static_cast<int>(i));
    t.points.push_back(d.points[i]);
    t.object_points.emplace_back(defined[i].x, defined[i].y, defined[i].z);
  }
  t.tags = 1;
  t.pose = d.pose;
  t.alt_pose = d.alt_pose;
  t.reprojection_error = d.reprojection_error;
  t.alt_reprojection_error = d.alt_reprojection_error;
  return t;
}

}  // namespace target
}  // namespace imagenets
