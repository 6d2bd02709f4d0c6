#include "imagenets/vision/point_cloud.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace imagenets {
namespace cloud {

int floatFieldOffset(const sensor_msgs::PointCloud2& cloud, const std::string& name) {
  for (const auto& f : cloud.fields) {
    if (f.name == name && f.datatype == sensor_msgs::PointField::FLOAT32) return static_cast<int>(f.offset);
  }
  return -1;
}

std::string checkCloud(const sensor_msgs::PointCloud2& cloud) {
  for (const char* axis : {"x", "y", "z"}) {
    const int off = floatFieldOffset(cloud, axis);
    if (off < 0) return std::string("no FLOAT32 field '") + axis + "'";
    if (static_cast<uint32_t>(off) + 4 > cloud.point_step) return std::string("field '") + axis + "' beyond point_step";
  }
  if (cloud.is_bigendian) return "big-endian clouds are not supported";
  if (static_cast<uint64_t>(cloud.row_step) < static_cast<uint64_t>(cloud.width) * cloud.point_step ||
      cloud.data.size() < static_cast<uint64_t>(cloud.row_step) * cloud.height) {
    return "data size " + std::to_string(cloud.data.size()) + " does not match " + std::to_string(cloud.width) + "x" +
           std::to_string(cloud.height) + " points of " + std::to_string(cloud.point_step) + " bytes";
  }
  return "";
}

sensor_msgs::PointCloud2Ptr makeCloud(const std::vector<PointXYZRGB>& points, bool colour) {
  sensor_msgs::PointCloud2Ptr c(new sensor_msgs::PointCloud2);
  const char* names[] = {"x", "y", "z", "rgb"};
  for (int i = 0; i < (colour ? 4 : 3); ++i) {
    sensor_msgs::PointField f;
    f.name = names[i];
    f.offset = 4 * i;
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    c->fields.push_back(f);
  }
  c->point_step = colour ? 16 : 12;
  c->height = 1;
  c->width = static_cast<uint32_t>(points.size());
  c->row_step = c->point_step * c->width;
  c->is_dense = true;
  c->is_bigendian = false;
  c->data.resize(c->row_step);
  uint8_t* out = c->data.data();
  for (const auto& p : points) {
    std::memcpy(out, &p.x, 4);
    std::memcpy(out + 4, &p.y, 4);
    std::memcpy(out + 8, &p.z, 4);
    if (colour) {
      const uint32_t rgb = (uint32_t(p.r) << 16) | (uint32_t(p.g) << 8) | uint32_t(p.b);
      std::memcpy(out + 12, &rgb, 4);
    }
    out += c->point_step;
  }
  return c;
}

std::vector<PointXYZRGB> readPoints(const sensor_msgs::PointCloud2& cloud, bool* has_colour) {
  const std::string problem = checkCloud(cloud);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const int ox = floatFieldOffset(cloud, "x"), oy = floatFieldOffset(cloud, "y"), oz = floatFieldOffset(cloud, "z");
  int orgb = -1;
  for (const auto& f : cloud.fields) {
    if ((f.name == "rgb" || f.name == "rgba") && f.offset + 4 <= cloud.point_step) orgb = static_cast<int>(f.offset);
  }
  if (has_colour) *has_colour = orgb >= 0;
  std::vector<PointXYZRGB> points;
  points.reserve(static_cast<size_t>(cloud.width) * cloud.height);
  for (uint32_t row = 0; row < cloud.height; ++row) {
    const uint8_t* p = cloud.data.data() + static_cast<size_t>(row) * cloud.row_step;
    for (uint32_t i = 0; i < cloud.width; ++i, p += cloud.point_step) {
      PointXYZRGB q;
      std::memcpy(&q.x, p + ox, 4);
      std::memcpy(&q.y, p + oy, 4);
      std::memcpy(&q.z, p + oz, 4);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
      q.r = q.g = q.b = 255;
      if (orgb >= 0) {
        uint32_t rgb;
        std::memcpy(&rgb, p + orgb, 4);
        q.r = (rgb >> 16) & 0xff;
        q.g = (rgb >> 8) & 0xff;
        q.b = rgb & 0xff;
      }
      points.push_back(q);
    }
  }
  return points;
}

void writePly(const sensor_msgs::PointCloud2& cloud, const std::string& path) {
  bool colour = false;
  std::vector<PointXYZRGB> points;
  try {
    points = readPoints(cloud, &colour);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\ncomment frame_id " << cloud.header.frame_id << "\nelement vertex "
        << points.size() << "\nproperty float x\nproperty float y\nproperty float z\n";
    if (colour) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    out << "end_header\n";
    for (const auto& p : points) {
      out.write(reinterpret_cast<const char*>(&p.x), 4);
      out.write(reinterpret_cast<const char*>(&p.y), 4);
      out.write(reinterpret_cast<const char*>(&p.z), 4);
      if (colour) {
        const char rgb[3] = {static_cast<char>(p.r), static_cast<char>(p.g), static_cast<char>(p.b)};
        out.write(rgb, 3);
      }
    }
    if (!out) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write '" + path + "'");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

}  // namespace cloud
}  // namespace imagenets
