#include <opencv2/imgproc.hpp>

#include "imagenets/register_block.h"
#include "polygon_ports.h"

namespace imagenets {
namespace blocks {

// Polygon approximation (Douglas-Peucker): each contour becomes a polygon with few vertices that
// stays within `epsilon` of it.
class ApproximatePolygons : public Block {
 public:
  ApproximatePolygons() {
    addInput<imagenets::Polygons>("contours", "closed contours");
    addOutput<imagenets::Polygons>("polygons", "one polygon per contour, same order");
    addProperty<double>("epsilon", 0.02,
                        "largest distance from the contour, as a fraction of its perimeter (if < 1) or in pixels")
        .range(0, 1000);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const auto contours = inputPolygons(ctx, "contours", &header);
    const double epsilon = ctx.property<double>("epsilon");
    imagenets::Polygons::Ptr out(new imagenets::Polygons);
    out->header = header;
    for (const auto& c : contours) {
      std::vector<cv::Point2f> approx;
      if (c.size() >= 2) {
        cv::approxPolyDP(c, approx, epsilon < 1 ? epsilon * cv::arcLength(c, true) : epsilon, true);
      } else {
        approx = c;
      }
      out->polygons.push_back(toPolygonMsg(approx));
    }
    ctx.output("polygons", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ApproximatePolygons, "imagenets/ApproximatePolygons", "features",
                         "Douglas-Peucker polygon approximation of contours");
