#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"
#include "polygon_ports.h"

namespace imagenets {
namespace blocks {

// Contour extraction: the borders of the white regions of a binary image (Suzuki-Abe border
// following), largest area first.
class FindContours : public Block {
 public:
  FindContours() {
    addInput<sensor_msgs::Image>("image", "binary mono8 image (non-zero = object)");
    addOutput<imagenets::Polygons>("contours", "one closed polygon per border, pixel coordinates, largest first");
    addProperty<std::string>("mode", "external", "external: outer borders only; all: holes too")
        .choices({"external", "all"});
    addProperty<double>("min_area", 10.0, "drop contours enclosing fewer square pixels").range(0, 1e9);
    addProperty<int>("max_count", 1000, "keep at most this many (the largest)").range(1, 1000000);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8"}, nullptr, &header);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(in, contours, ctx.property<std::string>("mode") == "external" ? cv::RETR_EXTERNAL : cv::RETR_LIST,
                     cv::CHAIN_APPROX_SIMPLE);
    const double min_area = ctx.property<double>("min_area");
    std::vector<std::pair<double, size_t>> kept;
    for (size_t i = 0; i < contours.size(); ++i) {
      const double area = cv::contourArea(contours[i]);
      if (area >= min_area) kept.emplace_back(area, i);
    }
    std::sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    kept.resize(std::min(kept.size(), static_cast<size_t>(ctx.property<int>("max_count"))));
    imagenets::Polygons::Ptr out(new imagenets::Polygons);
    out->header = header;
    for (const auto& k : kept) out->polygons.push_back(toPolygonMsg(contours[k.second]));
    ctx.output("contours", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::FindContours, "imagenets/FindContours", "features",
                         "Contours of the regions of a binary image");
