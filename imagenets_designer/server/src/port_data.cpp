#include "port_data.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <cstring>
#include <sstream>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <visualization_msgs/MarkerArray.h>

#include "net_state_json.h"

namespace imagenets {
namespace designer {

namespace {

std::string frame(const nlohmann::json& header, const std::string& payload) {
  const std::string h = jsonText(header);
  std::string out(4, '\0');
  const uint32_t n = static_cast<uint32_t>(h.size());
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((n >> (8 * i)) & 0xff);
  out += h;
  out += payload;
  return out;
}

// An image any encoding as 8-bit gray or BGR for a thumbnail: depth and float images are
// stretched from their smallest to their largest finite value.
cv::Mat displayable(const sensor_msgs::Image& msg) {
  namespace enc = sensor_msgs::image_encodings;
  auto shared = cv_bridge::toCvCopy(msg);
  cv::Mat m = shared->image;
  const std::string& e = msg.encoding;
  if (e == enc::RGB8) cv::cvtColor(m, m, cv::COLOR_RGB2BGR);
  else if (e == enc::RGBA8) cv::cvtColor(m, m, cv::COLOR_RGBA2BGR);
  else if (e == enc::BGRA8) cv::cvtColor(m, m, cv::COLOR_BGRA2BGR);
  if (m.depth() != CV_8U) {
    cv::Mat f;
    m.convertTo(f, CV_32F);
    cv::Mat finite = f == f;  // NaN != NaN
    double lo = 0, hi = 0;
    cv::minMaxLoc(f, &lo, &hi, nullptr, nullptr, finite.channels() == 1 ? finite : cv::Mat());
    f.setTo(lo, ~finite);
    f.convertTo(m, CV_8U, hi > lo ? 255.0 / (hi - lo) : 1.0, hi > lo ? -lo * 255.0 / (hi - lo) : 0.0);
  }
  if (m.channels() == 4) cv::cvtColor(m, m, cv::COLOR_BGRA2BGR);
  if (m.channels() != 1 && m.channels() != 3) {
    std::vector<cv::Mat> planes;
    cv::split(m, planes);
    m = planes.front();
  }
  return m;
}

std::string imagePayload(const sensor_msgs::Image& msg, const std::string& mode, nlohmann::json& header) {
  header["width"] = msg.width;
  header["height"] = msg.height;
  header["encoding"] = msg.encoding;
  if (mode == "full") {
    header["format"] = "raw";
    header["step"] = msg.step;
    header["is_bigendian"] = msg.is_bigendian != 0;
    return std::string(msg.data.begin(), msg.data.end());
  }
  cv::Mat m = displayable(msg);
  if (m.cols > kPreviewWidth) {
    const int h = std::max(1, static_cast<int>(std::lround(m.rows * static_cast<double>(kPreviewWidth) / m.cols)));
    cv::resize(m, m, cv::Size(kPreviewWidth, h), 0, 0, cv::INTER_AREA);
  }
  // Pixels, not a JPEG: the page draws them in the task that receives them, where a compressed
  // thumbnail waits for the browser's asynchronous decode (4 ms on an idle page, over 20 ms while it
  // re-renders after a run). At most 256 x 192 x 3 bytes.
  if (!m.isContinuous()) m = m.clone();
  header["format"] = "pixels";
  header["channels"] = m.channels();
  header["preview_width"] = m.cols;
  header["preview_height"] = m.rows;
  return std::string(reinterpret_cast<const char*>(m.data), m.total() * m.elemSize());
}

std::string cloudPayload(const sensor_msgs::PointCloud2& cloud, nlohmann::json& header) {
  bool has_rgb = false;
  for (const auto& f : cloud.fields) has_rgb = has_rgb || f.name == "rgb" || f.name == "rgba";
  std::string out;
  out.reserve(static_cast<size_t>(cloud.width) * cloud.height * 16);
  sensor_msgs::PointCloud2ConstIterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  std::unique_ptr<sensor_msgs::PointCloud2ConstIterator<uint8_t>> rgb;
  if (has_rgb) {
    const bool rgba = std::none_of(cloud.fields.begin(), cloud.fields.end(), [](const auto& f) { return f.name == "rgb"; });
    rgb = std::make_unique<sensor_msgs::PointCloud2ConstIterator<uint8_t>>(cloud, rgba ? "rgba" : "rgb");
  }
  size_t points = 0;
  for (; x != x.end(); ++x, ++y, ++z) {
    uint8_t color[4] = {255, 255, 255, 0};
    if (rgb) {
      color[0] = (*rgb)[2];  // PCL packs b, g, r in memory order
      color[1] = (*rgb)[1];
      color[2] = (*rgb)[0];
      ++*rgb;
    }
    if (!std::isfinite(*x) || !std::isfinite(*y) || !std::isfinite(*z)) continue;
    const float xyz[3] = {*x, *y, *z};
    out.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    out.append(reinterpret_cast<const char*>(color), sizeof color);
    ++points;
  }
  header["format"] = "xyzrgb";
  header["points"] = points;
  header["frame_id"] = cloud.header.frame_id;
  return out;
}

nlohmann::json poseJson(const geometry_msgs::Point& p, const geometry_msgs::Quaternion& q) {
  const double roll = std::atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y));
  const double pitch = std::asin(std::max(-1.0, std::min(1.0, 2 * (q.w * q.y - q.z * q.x))));
  const double yaw = std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
  return {{"xyz", {p.x, p.y, p.z}}, {"rpy", {roll, pitch, yaw}}, {"q", {q.x, q.y, q.z, q.w}}};
}

nlohmann::json xyzJson(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
nlohmann::json colorJson(const std_msgs::ColorRGBA& c) { return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}}; }

// A scene (the Joiner3D's) holds clouds of many thousand points: written directly, not through
// the printer.
nlohmann::json markersJson(const visualization_msgs::MarkerArray& array) {
  nlohmann::json markers = nlohmann::json::array();
  for (const auto& m : array.markers) {
    nlohmann::json points = nlohmann::json::array(), colors = nlohmann::json::array();
    for (const auto& p : m.points) points.push_back(xyzJson(p.x, p.y, p.z));
    for (const auto& c : m.colors) colors.push_back(colorJson(c));
    const auto& o = m.pose.orientation;
    markers.push_back({{"ns", m.ns},
                       {"id", m.id},
                       {"type", m.type},
                       {"action", m.action},
                       {"frame_id", m.header.frame_id},
                       {"pose",
                        {{"position", xyzJson(m.pose.position.x, m.pose.position.y, m.pose.position.z)},
                         {"orientation", {{"x", o.x}, {"y", o.y}, {"z", o.z}, {"w", o.w}}}}},
                       {"scale", xyzJson(m.scale.x, m.scale.y, m.scale.z)},
                       {"color", colorJson(m.color)},
                       {"points", points},
                       {"colors", colors},
                       {"text", m.text}});
  }
  return {{"markers", markers}};
}

}  // namespace

nlohmann::json printedMessageToJson(const std::string& printed) {
  struct Line {
    int indent;
    std::string key, value;
    bool array;
  };
  std::vector<Line> lines;
  std::istringstream in(printed);
  std::string raw;
  while (std::getline(in, raw)) {
    const size_t start = raw.find_first_not_of(' ');
    if (start == std::string::npos) continue;
    Line l{static_cast<int>(start), "", "", false};
    std::string rest = raw.substr(start);
    const size_t colon = rest.find(": ");
    if (colon == std::string::npos && rest.size() > 2 && rest.compare(rest.size() - 2, 2, "[]") == 0) {
      l.key = rest.substr(0, rest.size() - 2);
      l.array = true;
    } else if (colon != std::string::npos) {
      l.key = rest.substr(0, colon);
      l.value = rest.substr(colon + 2);
    } else if (!rest.empty() && rest.back() == ':') {
      l.key = rest.substr(0, rest.size() - 1);
    } else {
      continue;
    }
    lines.push_back(l);
  }
  auto scalar = [](const std::string& s) -> nlohmann::json {
    if (s.empty()) return s;
    char* end = nullptr;
    const double d = std::strtod(s.c_str(), &end);
    if (end && *end == '\0') {
      if (!std::isfinite(d)) return nullptr;
      return d;
    }
    return s;
  };
  size_t i = 0;
  std::function<nlohmann::json(int)> parseBlock = [&](int indent) {
    nlohmann::json obj = nlohmann::json::object();
    while (i < lines.size() && lines[i].indent >= indent) {
      const Line l = lines[i++];
      const bool nested = i < lines.size() && lines[i].indent > l.indent;
      if (l.array) {
        nlohmann::json arr = nlohmann::json::array();
        while (i < lines.size() && lines[i].indent > l.indent) {
          const Line item = lines[i++];
          const bool item_nested = i < lines.size() && lines[i].indent > item.indent;
          arr.push_back(item_nested ? parseBlock(lines[i].indent) : scalar(item.value));
        }
        obj[l.key] = arr;
      } else if (nested && l.value.empty()) {
        obj[l.key] = parseBlock(lines[i].indent);
      } else {
        obj[l.key] = scalar(l.value);
      }
    }
    return obj;
  };
  return parseBlock(0);
}

nlohmann::json messageToJson(const Value& value) {
  const std::string& type = value.type->name;
  if (type == "geometry_msgs/TransformStamped") {
    auto t = value.as<geometry_msgs::TransformStamped>();
    geometry_msgs::Point p;
    p.x = t->transform.translation.x;
    p.y = t->transform.translation.y;
    p.z = t->transform.translation.z;
    nlohmann::json out = poseJson(p, t->transform.rotation);
    out["frame_id"] = t->header.frame_id;
    out["child_frame_id"] = t->child_frame_id;
    return out;
  }
  if (type == "geometry_msgs/PoseStamped") {
    auto p = value.as<geometry_msgs::PoseStamped>();
    nlohmann::json out = poseJson(p->pose.position, p->pose.orientation);
    out["frame_id"] = p->header.frame_id;
    out["child_frame_id"] = "";
    return out;
  }
  if (type == "geometry_msgs/PoseArray") {
    auto a = value.as<geometry_msgs::PoseArray>();
    nlohmann::json poses = nlohmann::json::array();
    for (const auto& p : a->poses) poses.push_back(poseJson(p.position, p.orientation));
    return {{"frame_id", a->header.frame_id}, {"poses", poses}};
  }
  if (type == "visualization_msgs/MarkerArray") return markersJson(*value.as<visualization_msgs::MarkerArray>());
  std::ostringstream printed;
  value.type->printYaml(printed, value);
  return printedMessageToJson(printed.str());
}

std::string encodePortFrame(const Value& value, const std::string& mode, nlohmann::json header) {
  header["mode"] = mode;
  if (!value) {
    header["format"] = "none";
    return frame(header, "");
  }
  header["type"] = value.type->name;
  if (value.type->name == "sensor_msgs/Image") {
    auto image = value.as<sensor_msgs::Image>();
    std::string payload = imagePayload(*image, mode, header);
    return frame(header, payload);
  }
  if (value.type->name == "sensor_msgs/PointCloud2") {
    auto cloud = value.as<sensor_msgs::PointCloud2>();
    std::string payload = cloudPayload(*cloud, header);
    return frame(header, payload);
  }
  header["format"] = "json";
  return frame(header, jsonText(messageToJson(value)));
}

bool decodePortFrame(const std::string& data, nlohmann::json& header, std::string& payload) {
  if (data.size() < 4) return false;
  uint32_t n = 0;
  for (int i = 0; i < 4; ++i) n |= static_cast<uint32_t>(static_cast<unsigned char>(data[i])) << (8 * i);
  if (data.size() < 4 + static_cast<size_t>(n)) return false;
  header = nlohmann::json::parse(data.substr(4, n), nullptr, false);
  if (header.is_discarded()) return false;
  payload = data.substr(4 + n);
  return true;
}

}  // namespace designer
}  // namespace imagenets
