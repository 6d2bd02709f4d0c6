#include <cmath>
#include <unordered_map>

#include "imagenets/vision/point_cloud.h"
#include "imagenets/register_block.h"
#include "imagenets/block.h"

namespace imagenets {
namespace blocks {

// Voxel-grid downsampling: one point per occupied cube of side `leaf_size`, at the centroid of
// the points in it (colour averaged too), like PCL's VoxelGrid.
class VoxelDownsample : public Block {
 public:
  VoxelDownsample() {
    addInput<sensor_msgs::PointCloud2>("cloud", "any cloud with FLOAT32 x, y, z (rgb kept if present)");
    addOutput<sensor_msgs::PointCloud2>("cloud", "x, y, z (+ rgb), one point per voxel");
    addProperty<double>("leaf_size", 0.01, "voxel side (m)").range(1e-6, 1000);
    addProperty<int>("min_points", 1, "drop voxels with fewer points (noise)").range(1, 1000000);
  }

  void process(Context& ctx) override {
    auto in = ctx.input<sensor_msgs::PointCloud2>("cloud");
    if (!in) throw BlockError("input 'cloud': missing");
    bool colour = false;
    std::vector<cloud::PointXYZRGB> points;
    try {
      points = cloud::readPoints(*in, &colour);
    } catch (const std::invalid_argument& e) {
      throw BlockError(std::string("input 'cloud': ") + e.what());
    }
    const double leaf = ctx.property<double>("leaf_size");
    const size_t min_points = static_cast<size_t>(ctx.property<int>("min_points"));
    struct Sum {
      double x = 0, y = 0, z = 0, r = 0, g = 0, b = 0;
      size_t n = 0;
    };
    std::unordered_map<uint64_t, Sum> voxels;
    std::vector<uint64_t> order;  // first-seen order keeps the output deterministic
    for (const auto& p : points) {
      const int64_t ix = static_cast<int64_t>(std::floor(p.x / leaf)), iy = static_cast<int64_t>(std::floor(p.y / leaf)),
                    iz = static_cast<int64_t>(std::floor(p.z / leaf));
      if (std::abs(ix) >= (1 << 20) || std::abs(iy) >= (1 << 20) || std::abs(iz) >= (1 << 20)) {
        throw BlockError("property 'leaf_size': " + std::to_string(leaf) + " m is too small for the cloud's extent");
      }
      const uint64_t key = (uint64_t(ix + (1 << 20)) << 42) | (uint64_t(iy + (1 << 20)) << 21) | uint64_t(iz + (1 << 20));
      auto [it, fresh] = voxels.try_emplace(key);
      if (fresh) order.push_back(key);
      Sum& s = it->second;
      s.x += p.x, s.y += p.y, s.z += p.z, s.r += p.r, s.g += p.g, s.b += p.b;
      ++s.n;
    }
    std::vector<cloud::PointXYZRGB> out_points;
    out_points.reserve(order.size());
    for (uint64_t key : order) {
      const Sum& s = voxels[key];
      if (s.n < min_points) continue;
      cloud::PointXYZRGB p;
      p.x = static_cast<float>(s.x / s.n);
      p.y = static_cast<float>(s.y / s.n);
      p.z = static_cast<float>(s.z / s.n);
      p.r = static_cast<uint8_t>(std::lround(s.r / s.n));
      p.g = static_cast<uint8_t>(std::lround(s.g / s.n));
      p.b = static_cast<uint8_t>(std::lround(s.b / s.n));
      out_points.push_back(p);
    }
    auto out = cloud::makeCloud(out_points, colour);
    out->header = in->header;
    ctx.output("cloud", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::VoxelDownsample, "imagenets/VoxelDownsample", "stereo",
                         "Voxel-grid downsampling of a point cloud");
