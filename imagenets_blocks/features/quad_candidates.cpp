#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"
#include "imagenets/vision/quadrilateral.h"
#include "polygon_ports.h"

namespace imagenets {
namespace blocks {

// Quadrilateral candidates (e.g. for square markers): contours that approximate to a convex
// quadrilateral of sufficient size, with corners refined to sub-pixel accuracy on the gray image
// (cv::cornerSubPix). Corners are ordered clockwise in the image (x right, y down), starting with
// the one nearest the top-left.
class QuadCandidates : public Block {
 public:
  QuadCandidates() {
    addInput<imagenets::Polygons>("contours", "closed contours (e.g. from FindContours)");
    addInput<sensor_msgs::Image>("image", "the mono8 gray image the contours come from (for sub-pixel corners)");
    addOutput<imagenets::Polygons>("quads", "4-vertex polygons, sub-pixel corners, largest first");
    addProperty<double>("epsilon", 0.03, "polygon approximation tolerance as a fraction of the perimeter").range(0.001, 0.5);
    addProperty<double>("min_side", 10.0, "shortest allowed side (pixels)").range(1, 100000);
    addProperty<double>("min_area", 100.0, "smallest allowed area (square pixels)").range(0, 1e10);
    addProperty<int>("refine_window", 5, "half size of the sub-pixel search window; 0: no refinement").range(0, 50);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const auto contours = inputPolygons(ctx, "contours", &header);
    const cv::Mat gray = inputImage(ctx, "image", {"mono8"});
    const double epsilon = ctx.property<double>("epsilon"), min_side = ctx.property<double>("min_side");
    const double min_area = ctx.property<double>("min_area");
    const int window = ctx.property<int>("refine_window");
    // Corners too near the border cannot be refined reliably (and the quad may be cut off).
    const cv::Rect2f inside(window + 1, window + 1, gray.cols - 2 * window - 2, gray.rows - 2 * window - 2);
    std::vector<std::pair<double, std::vector<cv::Point2f>>> quads;
    for (const auto& c : contours) {
      const auto corners = marker::convexQuadrilateral(c, epsilon, min_side, inside);
      if (!corners) continue;
      std::vector<cv::Point2f> quad(corners->begin(), corners->end());
      const double area = std::abs(cv::contourArea(quad));
      if (area < min_area) continue;
      startTopLeft(quad);
      quads.emplace_back(area, quad);
    }
    if (window > 0 && !quads.empty()) {
      std::vector<cv::Point2f> corners;
      for (const auto& q : quads) corners.insert(corners.end(), q.second.begin(), q.second.end());
      // The window must stay smaller than the shortest side, or neighbouring corners pull each other.
      cv::cornerSubPix(gray, corners, cv::Size(window, window), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 40, 0.001));
      for (size_t i = 0; i < quads.size(); ++i) std::copy_n(corners.begin() + 4 * i, 4, quads[i].second.begin());
    }
    std::sort(quads.begin(), quads.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    imagenets::Polygons::Ptr out(new imagenets::Polygons);
    out->header = header;
    for (const auto& q : quads) out->polygons.push_back(toPolygonMsg(q.second));
    ctx.output("quads", out);
  }

 private:
  // Clockwise already (convexQuadrilateral): start with the corner nearest the top-left.
  static void startTopLeft(std::vector<cv::Point2f>& q) {
    int first = 0;
    for (int i = 1; i < 4; ++i) {
      if (q[i].x + q[i].y < q[first].x + q[first].y) first = i;
    }
    std::rotate(q.begin(), q.begin() + first, q.end());
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::QuadCandidates, "imagenets/QuadCandidates", "features",
                         "Convex quadrilaterals from contours, sub-pixel corners");
