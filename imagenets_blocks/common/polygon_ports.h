// imagenets/Polygons <-> OpenCV point lists (private to the features and drawing blocks).
#pragma once

#include <cmath>
#include <vector>

#include <imagenets/Polygons.h>
#include <opencv2/core.hpp>

#include "imagenets/block.h"

namespace imagenets {
namespace blocks {

template <class P>
geometry_msgs::Polygon toPolygonMsg(const std::vector<P>& points) {
  geometry_msgs::Polygon poly;
  poly.points.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    poly.points[i].x = static_cast<float>(points[i].x);
    poly.points[i].y = static_cast<float>(points[i].y);
  }
  return poly;
}

// Every polygon of an input as float points; BlockError naming the port if missing or if a
// vertex is not finite.
inline std::vector<std::vector<cv::Point2f>> inputPolygons(const Context& ctx, const std::string& port,
                                                           std_msgs::Header* header = nullptr) {
  auto msg = ctx.input<imagenets::Polygons>(port);
  if (!msg) throw BlockError("input '" + port + "': no polygons");
  if (header) *header = msg->header;
  std::vector<std::vector<cv::Point2f>> polys(msg->polygons.size());
  for (size_t i = 0; i < polys.size(); ++i) {
    for (const auto& p : msg->polygons[i].points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
        throw BlockError("input '" + port + "': polygon " + std::to_string(i) + " has a vertex that is not finite");
      }
      polys[i].emplace_back(p.x, p.y);
    }
  }
  return polys;
}

}  // namespace blocks
}  // namespace imagenets
