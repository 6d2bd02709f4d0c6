// A contour's outline as a convex quadrilateral: the first step of the square-marker detector
// (marker.cpp) and of the QuadCandidates block.
#pragma once

#include <array>
#include <optional>

#include <opencv2/core.hpp>

namespace imagenets {
namespace marker {

// The polygon approximation of `contour` (points, int or float; Douglas-Peucker, tolerance `epsilon` x its perimeter) if it
// is a convex quadrilateral whose sides are all at least `min_side` pixels long and whose corners lie
// inside `inside`; its corners clockwise in the image (x right, y down). Nothing otherwise.
std::optional<std::array<cv::Point2f, 4>> convexQuadrilateral(cv::InputArray contour, double epsilon,
                                                               double min_side, const cv::Rect2f& inside);

}  // namespace marker
}  // namespace imagenets
