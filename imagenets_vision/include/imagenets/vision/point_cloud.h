// Point cloud helpers (sensor_msgs/PointCloud2 without PCL): field access, building XYZ(RGB)
// clouds, and writing PLY files. Used by the stereo blocks and the command line tool.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <sensor_msgs/PointCloud2.h>

namespace imagenets {
namespace cloud {

struct PointXYZRGB {
  float x, y, z;
  uint8_t r, g, b;
};

// Byte offset of a FLOAT32 field, or -1 if the cloud has no such field of that type.
int floatFieldOffset(const sensor_msgs::PointCloud2& cloud, const std::string& name);
// Checks a cloud is usable: x, y, z FLOAT32 fields, consistent sizes. Returns "" or the problem.
std::string checkCloud(const sensor_msgs::PointCloud2& cloud);

// An unorganised (height 1), dense cloud with fields x, y, z (FLOAT32) and, when `colour`, rgb
// (FLOAT32 holding packed 0x00RRGGBB, as PCL and rviz read it).
sensor_msgs::PointCloud2Ptr makeCloud(const std::vector<PointXYZRGB>& points, bool colour);
// Every finite point of a cloud (colour 255,255,255 when the cloud has no rgb/rgba field).
std::vector<PointXYZRGB> readPoints(const sensor_msgs::PointCloud2& cloud, bool* has_colour = nullptr);

// Writes a binary little-endian PLY (x y z as float, red green blue as uchar when the cloud has
// colour) atomically (temporary file + rename). Throws std::runtime_error naming the path.
void writePly(const sensor_msgs::PointCloud2& cloud, const std::string& path);

}  // namespace cloud
}  // namespace imagenets
