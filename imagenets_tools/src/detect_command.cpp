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

int run(const Args& args) {
  std::string marker_path, target_path, camera_path, net_path;
  marker::ThresholdMode mode;
  bool fixed = false, feedback = false, coarse_to_fine = false;
  std::vector<std::string> images;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--marker") marker_path = flagValue(args, i);
    else if (a == "--target") target_path = flagValue(args, i);
    else if (a == "--camera") camera_path = flagValue(args, i);
    else if (a == "--net") net_path = flagValue(args, i);
    else if (a == "--threshold") {
      const std::string v = flagValue(args, i);
      char* end = nullptr;
      const long t = std::strtol(v.c_str(), &end, 10);
      if (*end || t < 0 || t > 255) throw UsageError("--threshold '" + v + "' is not an integer 0..255");
      mode.kind = marker::ThresholdMode::Kind::Fixed;
      mode.fixed = static_cast<int>(t);
      fixed = true;
    } else if (a == "--feedback") {
      const std::string v = flagValue(args, i);
      if (std::sscanf(v.c_str(), "%lf:%lf:%lf", &mode.from, &mode.to, &mode.step) != 3 || !(mode.step > 0) ||
          mode.to < mode.from || mode.from < 0 || mode.to > 255) {
        throw UsageError("--feedback '" + v + "' is not FROM:TO:STEP within 0..255");
      }
      mode.kind = marker::ThresholdMode::Kind::Range;
      feedback = true;
    } else if (a == "--coarse-to-fine") {
      mode.search = "coarse_to_fine";
      coarse_to_fine = true;
    }
    else if (a.size() > 1 && a[0] == '-') throw unknownArgument(a);
    else images.push_back(a);
  }
  if (fixed && feedback) throw UsageError("give --threshold or --feedback, not both");
  if (coarse_to_fine && !feedback) {
    throw UsageError("--coarse-to-fine orders a --feedback FROM:TO:STEP range (without one the net's own feedback runs)");
  }
  if (!marker_path.empty() && !target_path.empty()) throw UsageError("give --marker or --target, not both");
  if (marker_path.empty() && target_path.empty()) throw UsageError("--marker MARKER.yaml or --target TARGET.yaml is required");
  if (camera_path.empty()) throw UsageError("--camera CAMERA.yaml is required");
  if (images.empty()) throw UsageError("no IMAGE given");
  if (net_path.empty()) net_path = defaultNet();

  if (!boost::filesystem::exists(camera_path)) {
    std::cerr << "imagenets detect: --camera: no such file '" << camera_path << "'\n";
    return 1;
  }
  boost::shared_ptr<sensor_msgs::CameraInfo> info;
  std::string camera_name;
  try {
    info = boost::make_shared<sensor_msgs::CameraInfo>(readCameraInfo(camera_path, &camera_name));
  } catch (const std::exception& e) {
    std::cerr << "imagenets detect: --camera: " << e.what() << "\n";
    return 1;
  }
  info->header.frame_id = camera_name.empty() ? "camera" : camera_name + "_optical_frame";
  // A target file: named errors before any image; a square marker's goes on as --marker.
  std::shared_ptr<const target::TargetDescription> target;
  if (!target_path.empty()) {
    try {
      target = target::TargetDescription::loadCached(target_path);
    } catch (const std::exception& e) {
      std::cerr << "imagenets detect: --target: " << e.what() << "\n";
      return 1;
    }
    if (target->type == target::TargetType::SquareMarker) {
      marker_path = target->marker_file;
      target.reset();
    } else if (fixed || feedback) {
      throw UsageError("--threshold / --feedback belong to a square marker; " + target_path + " is a " +
                       target->typeName() + " target (found without a threshold)");
    }
  }
  std::unique_ptr<marker::MarkerDetectionNet> net;
  if (!target) {
    try {
      marker::MarkerDescription::load(marker_path);  // named error for a bad marker file, before any image
      net.reset(new marker::MarkerDetectionNet(net_path, marker_path, mode, 0));
    } catch (const std::exception& e) {
      std::cerr << "imagenets detect: " << e.what() << "\n";
      return 1;
    }
  }
  const render::CameraModel camera = render::CameraModel::fromCameraInfo(*info);

  int errors = 0;
  std::ostringstream out;
  out << std::setprecision(9);
  for (const auto& path : images) {
    out << "- image: " << quoted(path) << "\n";
    std::string error;
    cv::Mat image;
    if (!boost::filesystem::exists(path)) error = "no such file";
    else if ((image = cv::imread(path, cv::IMREAD_COLOR)).empty()) error = "cannot read image (not an image file?)";
    else if (image.cols != static_cast<int>(info->width) || image.rows != static_cast<int>(info->height)) {
      error = "image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + " but camera '" +
              camera_path + "' is " + std::to_string(info->width) + "x" + std::to_string(info->height);
    }
    if (target && error.empty()) {
      cv::Mat gray;
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
      target::TargetDetection d;
      try {
        d = target::detectTarget(gray, camera, *target);
      } catch (const std::exception& e) {
        error = e.what();
      }
      if (error.empty()) {
        printTargetDetection(out, *target, d);
        continue;
      }
    }
    marker::MarkerDetectionNet::Result r;
    if (error.empty()) {
      std_msgs::Header header;
      header.frame_id = info->header.frame_id;
      r = net->run(cv_bridge::CvImage(header, "bgr8", image).toImageMsg(), info);
      error = r.error;
    }
    if (!error.empty()) {
      ++errors;
      out << "  error: " << quoted(path + ": " + error) << "\n";
      std::cerr << "imagenets detect: " << path << ": " << error << "\n";
      continue;
    }
    const auto& d = *r.detection;
    out << "  found: " << (d.found ? "true" : "false") << "\n";
    out << "  confidence: " << d.confidence << "\n";
    out << "  threshold: " << (std::isfinite(d.threshold) ? std::to_string(static_cast<int>(d.threshold)) : ".nan") << "\n";
    if (!d.found) continue;
    out << "  points:";
    for (const auto& p : d.points) out << (&p == &d.points.front() ? " [" : ", ") << "[" << p.x << ", " << p.y << "]";
    out << "]\n";
    out << "  translation: [" << d.pose.position.x << ", " << d.pose.position.y << ", " << d.pose.position.z << "]\n";
    out << "  quaternion: [" << d.pose.orientation.x << ", " << d.pose.orientation.y << ", " << d.pose.orientation.z
        << ", " << d.pose.orientation.w << "]\n";
    out << "  reprojection_error_px: " << d.reprojection_error << "\n";
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
                       run);

}  // namespace tool
}  // namespace imagenets
