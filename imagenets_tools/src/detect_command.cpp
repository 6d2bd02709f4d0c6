// `imagenets detect (--marker M.yaml | --target T.yaml) --camera C.yaml [--threshold T | --feedback FROM:TO:STEP] IMAGE...`
// Runs the robust marker detection net (config/nets/robust_marker_detection.yaml) on each image,
// with the threshold feedback the net declares unless --threshold or --feedback replace it, and
// prints YAML: one entry per image. A target file (imagenets_vision/config/targets/) of a square
// marker does the same with its marker; of AprilTags or a ChArUco board it runs their detection
// (imagenets_vision/target.h) and prints every corner found with its id. A bad image gets an
// `error` entry; the others are still processed; the exit code is then 1.
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <boost/filesystem.hpp>
#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/package.h>

#include "imagenets/tool/command.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/target.h"
#include "marker_study/marker_net.h"
#include "imagenets/vision/read_camera_info.h"
#include "imagenets/package_file.h"

namespace imagenets {
namespace tool {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

void printPoint(std::ostream& out, const cv::Point2d& p) { out << "[" << p.x << ", " << p.y << "]"; }

// One image's target detection: what was found, every corner with its id, the pose.
void printTargetDetection(std::ostream& out, const target::TargetDescription& t, const target::TargetDetection& d) {
  out << "  target: " << quoted(t.name) << "\n";
  out << "  type: " << t.typeName() << "\n";
  out << "  found: " << (d.found ? "true" : "false") << "\n";
  out << "  confidence: " << d.confidence << "\n";
  out << "  tags: " << d.tags << "\n";
  if (!d.found) {
    out << "  reason: " << quoted(d.reason) << "\n";
    return;
  }
  out << "  ids: [";
  for (size_t i = 0; i < d.ids.size(); ++i) out << (i ? ", " : "") << d.ids[i];
  out << "]\n  points: [";
  for (size_t i = 0; i < d.points.size(); ++i) {
    out << (i ? ", " : "");
    printPoint(out, d.points[i]);
  }
  out << "]\n";
  const Eigen::Quaterniond q(d.pose.rotation());
  out << "  translation: [" << d.pose.translation().x() << ", " << d.pose.translation().y() << ", "
      << d.pose.translation().z() << "]\n";
  out << "  quaternion: [" << q.x() << ", " << q.y() << ", " << q.z() << ", " << q.w() << "]\n";
  out << "  reprojection_error_px: " << d.reprojection_error << "\n";
}

std::string defaultNet() { return imagenets::packageFile("imagenets_blocks", "config/nets/robust_marker_detection.yaml"); }

void declare(Flags& f) {
  f.add()("marker", po::value<std::string>()->default_value(""), "the square marker (MARKER.yaml)")
      ("target", po::value<std::string>()->default_value(""), "a target file (square marker, AprilTags, ChArUco)")
      ("camera", po::value<std::string>()->default_value(""), "the camera's calibration (CAMERA.yaml)")
      ("threshold", po::value<int>(), "a fixed threshold 0..255 instead of the net's feedback")
      ("feedback", po::value<std::string>(), "FROM:TO:STEP: the feedback's threshold range instead of the net's")
      ("coarse-to-fine", po::bool_switch(), "search the --feedback range coarse to fine")
      ("net", po::value<std::string>()->default_value(""), "the detection net (default: robust_marker_detection.yaml)");
  f.operand("IMAGE", -1, "the images");
}

// What to detect in which images, checked.
struct Request {
  std::string marker_path, target_path, camera_path, net_path;
  marker::ThresholdMode mode;
  bool threshold_given = false;  // --threshold or --feedback
  std::vector<std::string> images;
};

marker::ThresholdMode thresholdMode(const Options& o) {
  marker::ThresholdMode mode;
  if (o.count("threshold") && o.count("feedback")) throw UsageError("give --threshold or --feedback, not both");
  if (o.count("threshold")) {
    const int t = o["threshold"].as<int>();
    if (t < 0 || t > 255) throw UsageError("--threshold '" + std::to_string(t) + "' is not an integer 0..255");
    mode.kind = marker::ThresholdMode::Kind::Fixed;
    mode.fixed = t;
  }
  if (o.count("feedback")) {
    const std::string v = o["feedback"].as<std::string>();
    if (std::sscanf(v.c_str(), "%lf:%lf:%lf", &mode.from, &mode.to, &mode.step) != 3 || !(mode.step > 0) ||
        mode.to < mode.from || mode.from < 0 || mode.to > 255) {
      throw UsageError("--feedback '" + v + "' is not FROM:TO:STEP within 0..255");
    }
    mode.kind = marker::ThresholdMode::Kind::Range;
  }
  if (o["coarse-to-fine"].as<bool>()) {
    if (!o.count("feedback")) {
      throw UsageError("--coarse-to-fine orders a --feedback FROM:TO:STEP range (without one the net's own feedback runs)");
    }
    mode.search = "coarse_to_fine";
  }
  return mode;
}

Request request(const Options& o) {
  Request r;
  r.mode = thresholdMode(o);
  r.threshold_given = o.count("threshold") || o.count("feedback");
  r.marker_path = o["marker"].as<std::string>();
  r.target_path = o["target"].as<std::string>();
  r.camera_path = o["camera"].as<std::string>();
  r.net_path = o["net"].as<std::string>();
  r.images = strings(o, "IMAGE");
  if (!r.marker_path.empty() && !r.target_path.empty()) throw UsageError("give --marker or --target, not both");
  if (r.marker_path.empty() && r.target_path.empty()) throw UsageError("--marker MARKER.yaml or --target TARGET.yaml is required");
  if (r.camera_path.empty()) throw UsageError("--camera CAMERA.yaml is required");
  if (r.images.empty()) throw UsageError("no IMAGE given");
  if (r.net_path.empty()) r.net_path = defaultNet();
  return r;
}

boost::shared_ptr<sensor_msgs::CameraInfo> loadCamera(const std::string& path) {
  if (!boost::filesystem::exists(path)) throw std::runtime_error("--camera: no such file '" + path + "'");
  boost::shared_ptr<sensor_msgs::CameraInfo> info;
  std::string camera_name;
  try {
    info = boost::make_shared<sensor_msgs::CameraInfo>(readCameraInfo(path, &camera_name));
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("--camera: ") + e.what());
  }
  info->header.frame_id = camera_name.empty() ? "camera" : camera_name + "_optical_frame";
  return info;
}

// A target file: named errors before any image. A square marker's goes on as --marker (null).
std::shared_ptr<const target::TargetDescription> loadTarget(Request& r) {
  if (r.target_path.empty()) return nullptr;
  std::shared_ptr<const target::TargetDescription> target;
  try {
    target = target::TargetDescription::loadCached(r.target_path);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("--target: ") + e.what());
  }
  if (target->type == target::TargetType::SquareMarker) {
    r.marker_path = target->marker_file;
    return nullptr;
  }
  if (r.threshold_given) {
    throw UsageError("--threshold / --feedback belong to a square marker; " + r.target_path + " is a " +
                     target->typeName() + " target (found without a threshold)");
  }
  return target;
}

// Why an image cannot be used ("" when it can).
std::string readImage(const std::string& path, const sensor_msgs::CameraInfo& info, const std::string& camera_path,
                      cv::Mat& image) {
  if (!boost::filesystem::exists(path)) return "no such file";
  if ((image = cv::imread(path, cv::IMREAD_COLOR)).empty()) return "cannot read image (not an image file?)";
  if (image.cols != static_cast<int>(info.width) || image.rows != static_cast<int>(info.height)) {
    return "image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + " but camera '" +
           camera_path + "' is " + std::to_string(info.width) + "x" + std::to_string(info.height);
  }
  return "";
}

void printMarkerDetection(std::ostream& out, const imagenets::MarkerDetection& d) {
  out << "  found: " << (d.found ? "true" : "false") << "\n";
  out << "  confidence: " << d.confidence << "\n";
  out << "  threshold: " << (std::isfinite(d.threshold) ? std::to_string(static_cast<int>(d.threshold)) : ".nan") << "\n";
  if (!d.found) return;
  out << "  points:";
  for (const auto& p : d.points) out << (&p == &d.points.front() ? " [" : ", ") << "[" << p.x << ", " << p.y << "]";
  out << "]\n";
  out << "  translation: [" << d.pose.position.x << ", " << d.pose.position.y << ", " << d.pose.position.z << "]\n";
  out << "  quaternion: [" << d.pose.orientation.x << ", " << d.pose.orientation.y << ", " << d.pose.orientation.z
      << ", " << d.pose.orientation.w << "]\n";
  out << "  reprojection_error_px: " << d.reprojection_error << "\n";
}

// The detection net, or the target's detection, on one readable image: its YAML, or the error.
std::string detectIn(const cv::Mat& image, const sensor_msgs::CameraInfoConstPtr& info, const render::CameraModel& camera,
                     const target::TargetDescription* target, marker::MarkerDetectionNet* net, std::ostream& out) {
  if (target) {
    cv::Mat gray;
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
    try {
      printTargetDetection(out, *target, target::detectTarget(gray, camera, *target));
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
  std_msgs::Header header;
  header.frame_id = info->header.frame_id;
  const marker::MarkerDetectionNet::Result r = net->run(cv_bridge::CvImage(header, "bgr8", image).toImageMsg(), info);
  if (r.error.empty()) printMarkerDetection(out, *r.detection);
  return r.error;
}

int run(const Options& o) {
  Request r = request(o);
  const boost::shared_ptr<sensor_msgs::CameraInfo> info = loadCamera(r.camera_path);
  const std::shared_ptr<const target::TargetDescription> target = loadTarget(r);
  std::unique_ptr<marker::MarkerDetectionNet> net;
  if (!target) {
    marker::MarkerDescription::load(r.marker_path);  // named error for a bad marker file, before any image
    net.reset(new marker::MarkerDetectionNet(r.net_path, r.marker_path, r.mode, 0));
  }
  const render::CameraModel camera = render::CameraModel::fromCameraInfo(*info);
  int errors = 0;
  std::ostringstream out;
  out << std::setprecision(9);
  for (const auto& path : r.images) {
    out << "- image: " << quoted(path) << "\n";
    cv::Mat image;
    std::string error = readImage(path, *info, r.camera_path, image);
    if (error.empty()) error = detectIn(image, info, camera, target.get(), net.get(), out);
    if (error.empty()) continue;
    ++errors;
    out << "  error: " << quoted(path + ": " + error) << "\n";
    std::cerr << "imagenets detect: " << path << ": " << error << "\n";
  }
  std::cout << out.str();
  return errors ? 1 : 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(detect, "detect",
                       "detect (--marker MARKER.yaml | --target TARGET.yaml) --camera CAMERA.yaml "
                       "[--threshold T | --feedback FROM:TO:STEP] [--coarse-to-fine] [--net NET.yaml] IMAGE...",
                       "find a square marker (robust detection net, its threshold feedback unless "
                       "--threshold/--feedback replace it) or a target (AprilTags, ChArUco: corners with ids) in "
                       "images; print YAML: points, confidence, pose",
                       declare, run);

}  // namespace tool
}  // namespace imagenets
