#include <imagenets/Polygons.h>
#include <opencv2/imgproc.hpp>

#include "polygon_ports.h"
#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Draws polygons (contours, quadrilaterals, detections' outlines) or their vertices as points on
// a copy of an image; a gray image becomes colour so the overlay stands out.
class DrawPolygons : public Block {
 public:
  DrawPolygons() {
    addInput<sensor_msgs::Image>("image", "mono8, bgr8 or rgb8");
    addInput<imagenets::Polygons>("polygons", "pixel coordinates of the image");
    addOutput<sensor_msgs::Image>("image", "bgr8 with the overlay");
    addProperty<std::string>("style", "outline", "outline: closed polygons; points: vertices only; both")
        .choices({"outline", "points", "both"});
    addProperty<std::vector<double>>("colour", std::vector<double>{0, 255, 0}, "B, G, R (0..255)");
    addProperty<int>("thickness", 2, "line width (pixels)").range(1, 50);
    addProperty<int>("point_radius", 3, "vertex dot radius (pixels)").range(1, 50);
    addProperty<bool>("label", false, "write the polygon index beside its first vertex");
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8"}, &encoding, &header);
    const auto polygons = inputPolygons(ctx, "polygons");
    const auto c = ctx.property<std::vector<double>>("colour");
    if (c.size() != 3) throw BlockError("property 'colour': " + std::to_string(c.size()) + " values, expected B, G, R");
    const cv::Scalar colour(c[0], c[1], c[2]);
    cv::Mat out;
    if (encoding == "mono8") cv::cvtColor(in, out, cv::COLOR_GRAY2BGR);
    else if (encoding == "rgb8") cv::cvtColor(in, out, cv::COLOR_RGB2BGR);
    else out = in.clone();
    const std::string style = ctx.property<std::string>("style");
    const int thickness = ctx.property<int>("thickness"), radius = ctx.property<int>("point_radius");
    const int shift = 4;  // sub-pixel vertices
    for (size_t i = 0; i < polygons.size(); ++i) {
      std::vector<cv::Point> pts;
      for (const auto& p : polygons[i]) pts.emplace_back(cvRound(p.x * (1 << shift)), cvRound(p.y * (1 << shift)));
      if (pts.empty()) continue;
      if (style != "points") cv::polylines(out, pts, true, colour, thickness, cv::LINE_AA, shift);
      if (style != "outline") {
        for (const auto& p : pts) cv::circle(out, p, radius << shift, colour, cv::FILLED, cv::LINE_AA, shift);
      }
      if (ctx.property<bool>("label")) {
        cv::putText(out, std::to_string(i), cv::Point(pts[0].x >> shift, pts[0].y >> shift) + cv::Point(4, -4),
                    cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1, cv::LINE_AA);
      }
    }
    ctx.output("image", toImageMsg(out, "bgr8", header));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::DrawPolygons, "imagenets/DrawPolygons", "visualization",
                         "Draws contours / polygons / points on an image");
