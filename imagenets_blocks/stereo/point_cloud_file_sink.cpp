#include "imagenets/vision/point_cloud.h"
#include "imagenets/register_block.h"
#include "imagenets/block.h"

namespace imagenets {
namespace blocks {

// Writes a point cloud as a binary PLY file (MeshLab, CloudCompare, PCL read it), atomically.
class PointCloudFileSink : public Block {
 public:
  PointCloudFileSink() {
    addInput<sensor_msgs::PointCloud2>("cloud", "cloud with FLOAT32 x, y, z (rgb written as colour)");
    addProperty<std::string>("path", "", "output .ply file; relative to the net file").path();
  }

  void process(Context& ctx) override {
    auto in = ctx.input<sensor_msgs::PointCloud2>("cloud");
    if (!in) throw BlockError("input 'cloud': missing");
    const auto path = ctx.property<std::string>("path");
    if (path.empty()) throw BlockError("property 'path' is empty");
    try {
      cloud::writePly(*in, path);
    } catch (const std::runtime_error& e) {
      throw BlockError(e.what());
    }
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::PointCloudFileSink, "imagenets/PointCloudFileSink", "stereo",
                         "Writes a point cloud as a PLY file");
