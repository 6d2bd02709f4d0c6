#include "imagenets/vision/quadrilateral.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace imagenets {
namespace marker {

std::optional<std::array<cv::Point2f, 4>> convexQuadrilateral(cv::InputArray contour, double epsilon,
                                                               double min_side, const cv::Rect2f& inside) {
  if (contour.total() < 4) return std::nullopt;
  // The approximation's corners are points of the contour, so its perimeter is at most the
  // contour's: a contour shorter than four sides cannot give one (and most noise is cut here).
  const double perimeter = cv::arcLength(contour, true);
  if (perimeter < 4 * min_side) return std::nullopt;
  cv::Mat approx;  // of the contour's point type
  cv::approxPolyDP(contour, approx, epsilon * perimeter, true);
  if (approx.total() != 4 || !cv::isContourConvex(approx)) return std::nullopt;
  std::array<cv::Point2f, 4> quad;
  approx.reshape(2, 4).convertTo(cv::Mat(4, 1, CV_32FC2, quad.data()), CV_32F);
  for (int k = 0; k < 4; ++k) {
    if (cv::norm(quad[k] - quad[(k + 1) % 4]) < min_side || !inside.contains(quad[k])) return std::nullopt;
  }
  // Positive signed area with y down is clockwise on screen.
  if (cv::contourArea(approx, true) < 0) std::reverse(quad.begin(), quad.end());
  return quad;
}

}  // namespace marker
}  // namespace imagenets
