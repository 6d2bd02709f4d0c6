#include "imagenets/vision/read_camera_info.h"

#include <stdexcept>

#include <boost/filesystem/path.hpp>
#include <camera_calibration_parsers/parse.h>
#include <yaml-cpp/yaml.h>

namespace imagenets {
namespace {

// A matrix entry `key: {rows: R, cols: C, data: [...]}` whose R x C must match data and, where ROS
// fixes it, the shape (0: any).
void checkMatrix(const YAML::Node& root, const std::string& key, unsigned rows, unsigned cols,
                 const std::string& where) {
  const YAML::Node m = root[key];
  if (!m) return;  // the parser names what it misses
  const std::string at = where + ": '" + key + "'";
  if (!m.IsMap()) throw std::runtime_error(at + " is not a map of rows, cols and data");
  long r = 0, c = 0;
  try {
    r = m["rows"].as<long>();
    c = m["cols"].as<long>();
  } catch (const YAML::Exception&) {
    throw std::runtime_error(at + ": rows and cols must be integers");
  }
  if ((rows && r != rows) || (cols && c != cols) || r < 0 || c < 0) {
    throw std::runtime_error(at + " is " + std::to_string(r) + "x" + std::to_string(c) + ", expected " +
                             (rows ? std::to_string(rows) : "N") + "x" + (cols ? std::to_string(cols) : "N"));
  }
  const YAML::Node data = m["data"];
  if (!data || !data.IsSequence()) throw std::runtime_error(at + ": 'data' must be a list of numbers");
  if (data.size() != static_cast<size_t>(r * c)) {
    throw std::runtime_error(at + ": " + std::to_string(r) + "x" + std::to_string(c) + " needs " +
                             std::to_string(r * c) + " numbers, 'data' has " + std::to_string(data.size()));
  }
  for (const auto& v : data) {
    try {
      v.as<double>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error(at + ": 'data' holds '" + (v.IsScalar() ? v.Scalar() : std::string("a non-number")) +
                               "', not a number");
    }
  }
}

}  // namespace

sensor_msgs::CameraInfo readCameraInfo(const std::string& path, std::string* camera_name) {
  const std::string where = "camera-info file '" + path + "'";
  const std::string ext = boost::filesystem::path(path).extension().string();
  if (ext == ".yaml" || ext == ".yml") {
    YAML::Node root;
    try {
      root = YAML::LoadFile(path);
    } catch (const YAML::BadFile&) {
      throw std::runtime_error("cannot read a camera model from '" + path + "': no such file, or not readable");
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(where + ": not valid YAML: " + e.what());
    }
    if (!root.IsMap()) throw std::runtime_error(where + ": not a YAML map");
    checkMatrix(root, "camera_matrix", 3, 3, where);
    checkMatrix(root, "distortion_coefficients", 1, 0, where);
    checkMatrix(root, "rectification_matrix", 3, 3, where);
    checkMatrix(root, "projection_matrix", 3, 4, where);
  }
  sensor_msgs::CameraInfo info;
  std::string name;
  if (!camera_calibration_parsers::readCalibration(path, name, info)) {
    throw std::runtime_error(where + ": not a camera calibration file (camera_calibration_parsers refused it)");
  }
  if (camera_name) *camera_name = name;
  return info;
}

}  // namespace imagenets
