// Plots as images: a generic x/y series plot with axes, ticks and labels, and the plot of a
// feedback sweep (paper Fig. 3.3: score over the tuned property, the chosen value marked).
// Used by the PlotFeedbackTrace / PlotSeries blocks and by the command line tool.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <imagenets/FeedbackTrace.h>
#include <opencv2/core.hpp>

namespace imagenets {
namespace plot {

struct Series {
  std::vector<double> x, y;  // same length; a NaN y is a missing value: a gap, marked on the x axis
  std::string label;         // legend text; empty: no legend entry
  cv::Scalar color{160, 80, 0};  // BGR
  bool lines = true;
  bool points = true;
};

struct Options {
  std::string title, x_label, y_label;
  int width = 640, height = 400;  // pixels (at least 160 x 120)
  // A vertical marker (e.g. the chosen value): drawn when finite.
  double marked_x = std::numeric_limits<double>::quiet_NaN();
  double marked_y = std::numeric_limits<double>::quiet_NaN();  // a filled dot on the marker when finite
  std::string marked_label;
  std::string note;  // a line of text under the title (e.g. "no valid candidate")
};

// Where data coordinates land in the image, so callers and tests can place things.
struct Axes {
  cv::Rect area;                  // the plot area inside the axes
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  cv::Point2d toPixel(double x, double y) const;
};

// Colours the plots use (BGR), exposed for tests and legends.
extern const cv::Scalar kMarkerColor;   // chosen value
extern const cv::Scalar kMissingColor;  // NaN samples

// A white BGR image (CV_8UC3) of options.width x options.height with axes, "nice" ticks
// (1, 2, 5 x 10^k) and their labels, every series, the marker and the legend. `axes` (optional)
// receives the data-to-pixel mapping. Throws std::invalid_argument for x/y of different length or
// a size below 160 x 120.
cv::Mat plotSeries(const std::vector<Series>& series, const Options& options, Axes* axes = nullptr);

// The plot of one feedback sweep: title "block.property -> score", score over the property
// value, NaN scores as missing, the chosen value marked (or "no valid candidate").
cv::Mat plotFeedbackTrace(const imagenets::FeedbackTrace& trace, int width, int height, Axes* axes = nullptr);

}  // namespace plot
}  // namespace imagenets
