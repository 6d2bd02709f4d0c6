#include "output_writer.h"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/image_encodings.h>

#include "imagenets/vision/plot.h"
#include "imagenets/vision/point_cloud.h"
#include <imagenets/FeedbackTrace.h>

namespace imagenets {
namespace tool {
namespace {

void commit(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

std::string writeImage(const sensor_msgs::Image& msg, const std::string& path) {
  namespace enc = sensor_msgs::image_encodings;
  cv_bridge::CvImageConstPtr cv = cv_bridge::toCvCopy(msg);
  cv::Mat out = cv->image;
  if (msg.encoding == enc::RGB8) cv::cvtColor(out, out, cv::COLOR_RGB2BGR);
  else if (msg.encoding == enc::RGBA8) cv::cvtColor(out, out, cv::COLOR_RGBA2BGRA);
  else if (out.depth() == CV_32F || out.depth() == CV_64F) {
    // Float images (disparity, depth): scale the finite range to 0..255 for viewing.
    cv::Mat finite = out == out;  // NaN != NaN
    double lo = 0, hi = 0;
    cv::minMaxLoc(out, &lo, &hi, nullptr, nullptr, finite);
    out.convertTo(out, CV_8U, hi > lo ? 255.0 / (hi - lo) : 1.0, hi > lo ? -lo * 255.0 / (hi - lo) : 0.0);
  }
  const std::string tmp = path + ".tmp.png";
  if (!cv::imwrite(tmp, out)) throw std::runtime_error("cannot write '" + path + "'");
  commit(tmp, path);
  return path;
}

}  // namespace

std::string writeValue(const Value& value, const std::string& dir, const std::string& stem) {
  if (!value) return "";
  const std::string base = dir + "/" + stem;
  std::string written;
  if (value.type->name == "sensor_msgs/Image") {
    written = writeImage(*value.as<sensor_msgs::Image>(), base + ".png");
  } else if (value.type->name == "sensor_msgs/PointCloud2") {
    // A cloud as YAML would be megabytes of numbers: PLY opens in MeshLab / CloudCompare.
    written = base + ".ply";
    cloud::writePly(*value.as<sensor_msgs::PointCloud2>(), written);
  } else {
    written = base + ".yaml";
    const std::string tmp = written + ".tmp";
    {
      std::ofstream out(tmp);
      out << std::setprecision(17);  // every double as it is: results can be compared exactly
      out << "# " << value.type->name << "\n";
      value.type->printYaml(out, value);
      if (!out) throw std::runtime_error("cannot write '" + written + "'");
    }
    commit(tmp, written);
  }
  if (value.type->name == "imagenets/FeedbackTrace") {
    // The sweep as a person wants to see it: score over the property, chosen value marked.
    cv::Mat plot = plot::plotFeedbackTrace(*value.as<FeedbackTrace>(), 800, 500);
    const std::string png = base + ".png", tmp = base + ".tmp.png";
    if (!cv::imwrite(tmp, plot)) throw std::runtime_error("cannot write '" + png + "'");
    commit(tmp, png);
  }
  return written;
}

}  // namespace tool
}  // namespace imagenets
