#include <cmath>
#include <cstring>

#include "imagenets/vision/point_cloud.h"
#include "imagenets/register_block.h"
#include "imagenets/block.h"

namespace imagenets {
namespace blocks {

// Keeps the points inside (or outside) an axis-aligned box, all fields kept.
class PointCloudCrop : public Block {
 public:
  PointCloudCrop() {
    addInput<sensor_msgs::PointCloud2>("cloud", "any cloud with FLOAT32 x, y, z");
    addOutput<sensor_msgs::PointCloud2>("cloud", "the points in the box (unorganised, same fields)");
    addProperty<std::vector<double>>("min", std::vector<double>{-1, -1, 0}, "box corner x, y, z (m), cloud frame");
    addProperty<std::vector<double>>("max", std::vector<double>{1, 1, 5}, "opposite box corner x, y, z (m)");
    addProperty<bool>("outside", false, "keep the points outside the box instead");
  }

  void process(Context& ctx) override {
    auto in = ctx.input<sensor_msgs::PointCloud2>("cloud");
    if (!in) throw BlockError("input 'cloud': missing");
    const std::string problem = cloud::checkCloud(*in);
    if (!problem.empty()) throw BlockError("input 'cloud': " + problem);
    const auto lo = ctx.property<std::vector<double>>("min"), hi = ctx.property<std::vector<double>>("max");
    if (lo.size() != 3 || hi.size() != 3) throw BlockError("properties 'min' and 'max' need 3 values (x, y, z)");
    for (int i = 0; i < 3; ++i) {
      if (!(lo[i] <= hi[i])) throw BlockError("property 'min' exceeds 'max' on axis " + std::string(1, "xyz"[i]));
    }
    const bool outside = ctx.property<bool>("outside");
    const int off[3] = {cloud::floatFieldOffset(*in, "x"), cloud::floatFieldOffset(*in, "y"), cloud::floatFieldOffset(*in, "z")};
    sensor_msgs::PointCloud2Ptr out(new sensor_msgs::PointCloud2);
    out->header = in->header;
    out->fields = in->fields;
    out->point_step = in->point_step;
    out->is_bigendian = false;
    out->height = 1;
    out->data.reserve(in->data.size());
    for (uint32_t row = 0; row < in->height; ++row) {
      const uint8_t* p = in->data.data() + static_cast<size_t>(row) * in->row_step;
      for (uint32_t i = 0; i < in->width; ++i, p += in->point_step) {
        bool inside = true, finite = true;
        for (int a = 0; a < 3; ++a) {
          float v;
          std::memcpy(&v, p + off[a], 4);
          finite = finite && std::isfinite(v);
          inside = inside && v >= lo[a] && v <= hi[a];
        }
        if (finite && inside != outside) out->data.insert(out->data.end(), p, p + in->point_step);
      }
    }
    out->width = static_cast<uint32_t>(out->data.size() / in->point_step);
    out->row_step = out->width * out->point_step;
    out->is_dense = true;
    ctx.output("cloud", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::PointCloudCrop, "imagenets/PointCloudCrop", "stereo",
                         "Keeps the points of a cloud inside a box");
