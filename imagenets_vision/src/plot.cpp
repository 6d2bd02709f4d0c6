#include "imagenets/vision/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace imagenets {
namespace plot {

const cv::Scalar kMarkerColor(0, 0, 220);
const cv::Scalar kMissingColor(0, 140, 255);

namespace {

const int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kInk(40, 40, 40), kGrid(225, 225, 225);

// A "nice" tick step (1, 2 or 5 x 10^k) giving about `target` intervals over `range`.
double niceStep(double range, int target) {
  const double raw = range / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  return magnitude * (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10);
}

std::string tickLabel(double v, double step) {
  char buf[32];
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6), std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buf;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& color,
          int align = -1 /* -1 left, 0 centre, 1 right */, int thickness = 1) {
  int base = 0;
  const cv::Size size = cv::getTextSize(s, kFont, scale, thickness, &base);
  at.x -= align < 0 ? 0 : align == 0 ? size.width / 2 : size.width;
  cv::putText(img, s, at, kFont, scale, color, thickness, cv::LINE_AA);
}

// The finite data range, padded; a degenerate range is widened around its value.
void range(double lo, double hi, double& out_lo, double& out_hi, double pad_fraction) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
    const double half = std::max(0.5, std::abs(lo) * 0.1);
    lo -= half, hi += half;
  }
  const double pad = (hi - lo) * pad_fraction;
  out_lo = lo - pad;
  out_hi = hi + pad;
}

}  // namespace

cv::Point2d Axes::toPixel(double x, double y) const {
  return {area.x + (x - x_min) / (x_max - x_min) * area.width,
          area.y + area.height - (y - y_min) / (y_max - y_min) * area.height};
}

namespace {

// Text size for a picture of this height.
double fontScale(const Options& options) { return std::clamp(options.height / 800.0, 0.35, 0.6); }

// The data's ranges (and the marked point's), padded, and the plot area inside the margins.
Axes axesFor(const std::vector<Series>& series, const Options& options) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const auto& s : series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("series '" + s.label + "': " + std::to_string(s.x.size()) + " x values but " +
                                  std::to_string(s.y.size()) + " y values");
    }
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i])) continue;
      x_lo = std::min(x_lo, s.x[i]), x_hi = std::max(x_hi, s.x[i]);
      if (std::isfinite(s.y[i])) y_lo = std::min(y_lo, s.y[i]), y_hi = std::max(y_hi, s.y[i]);
    }
  }
  if (std::isfinite(options.marked_x)) x_lo = std::min(x_lo, options.marked_x), x_hi = std::max(x_hi, options.marked_x);
  if (std::isfinite(options.marked_y)) y_lo = std::min(y_lo, options.marked_y), y_hi = std::max(y_hi, options.marked_y);
  Axes axes;
  range(x_lo, x_hi, axes.x_min, axes.x_max, 0.03);
  range(y_lo, y_hi, axes.y_min, axes.y_max, 0.08);
  const double scale = fontScale(options);
  const int left = static_cast<int>(70 * scale / 0.45), bottom = static_cast<int>(48 * scale / 0.45);
  const int top = options.note.empty() ? static_cast<int>(34 * scale / 0.45) : static_cast<int>(50 * scale / 0.45);
  const int right = 16;
  axes.area = cv::Rect(left, top, options.width - left - right, options.height - top - bottom);
  return axes;
}

// Vertical y label: drawn horizontally, then rotated into the left margin.
void drawYLabel(cv::Mat& img, const Axes& axes, const std::string& y_label, double scale) {
  int base = 0;
  const cv::Size size = cv::getTextSize(y_label, kFont, scale, 1, &base);
  cv::Mat label(size.height + base + 4, size.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(label, y_label, {2, size.height + 2}, kFont, scale, kInk, 1, cv::LINE_AA);
  cv::rotate(label, label, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int x0 = 2, y0 = std::max(0, axes.area.y + axes.area.height / 2 - label.rows / 2);
  if (label.rows + y0 <= img.rows && label.cols + x0 <= img.cols) label.copyTo(img(cv::Rect(x0, y0, label.cols, label.rows)));
}

// Ticks, grid, frame, title, note and axis labels.
void drawFrame(cv::Mat& img, const Axes& axes, const Options& options) {
  const double scale = fontScale(options);
  const double x_step = niceStep(axes.x_max - axes.x_min, std::max(2, axes.area.width / 90));
  const double y_step = niceStep(axes.y_max - axes.y_min, std::max(2, axes.area.height / 60));
  for (double v = std::ceil(axes.x_min / x_step) * x_step; v <= axes.x_max + 1e-9 * x_step; v += x_step) {
    const int px = cvRound(axes.toPixel(v, 0).x);
    cv::line(img, {px, axes.area.y}, {px, axes.area.br().y}, kGrid, 1);
    cv::line(img, {px, axes.area.br().y}, {px, axes.area.br().y + 5}, kInk, 1);
    text(img, tickLabel(v, x_step), {px, axes.area.br().y + static_cast<int>(20 * scale / 0.45)}, scale, kInk, 0);
  }
  for (double v = std::ceil(axes.y_min / y_step) * y_step; v <= axes.y_max + 1e-9 * y_step; v += y_step) {
    const int py = cvRound(axes.toPixel(0, v).y);
    cv::line(img, {axes.area.x, py}, {axes.area.br().x, py}, kGrid, 1);
    cv::line(img, {axes.area.x - 5, py}, {axes.area.x, py}, kInk, 1);
    text(img, tickLabel(v, y_step), {axes.area.x - 8, py + 4}, scale, kInk, 1);
  }
  cv::rectangle(img, axes.area, kInk, 1);
  text(img, options.title, {options.width / 2, static_cast<int>(22 * scale / 0.45)}, scale * 1.25, kInk, 0, 1);
  if (!options.note.empty()) {
    text(img, options.note, {options.width / 2, static_cast<int>(40 * scale / 0.45)}, scale, kMarkerColor, 0);
  }
  text(img, options.x_label, {axes.area.x + axes.area.width / 2, options.height - 8}, scale, kInk, 0);
  if (!options.y_label.empty()) drawYLabel(img, axes, options.y_label, scale);
}

// Data: lines between consecutive finite samples; a NaN breaks the line and is marked as a
// cross below the plot area. Then the marked x (dashed) and point. True when a value was missing.
bool drawData(cv::Mat& img, const Axes& axes, const std::vector<Series>& series, const Options& options) {
  cv::Mat plot_area = img(axes.area);
  Axes local = axes;
  local.area = cv::Rect(0, 0, axes.area.width, axes.area.height);
  const int shift = 4;  // sub-pixel drawing
  auto fixed = [&](const cv::Point2d& p) { return cv::Point(cvRound(p.x * (1 << shift)), cvRound(p.y * (1 << shift))); };
  bool any_missing = false;
  for (const auto& s : series) {
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i])) continue;
      if (!std::isfinite(s.y[i])) {
        any_missing = true;
        const cv::Point2d p = local.toPixel(s.x[i], axes.y_min);
        const int px = cvRound(p.x), py = local.area.height - 6;
        cv::line(plot_area, {px - 4, py - 4}, {px + 4, py + 4}, kMissingColor, 2);
        cv::line(plot_area, {px - 4, py + 4}, {px + 4, py - 4}, kMissingColor, 2);
        continue;
      }
      const cv::Point2d p = local.toPixel(s.x[i], s.y[i]);
      if (s.lines && i + 1 < s.x.size() && std::isfinite(s.x[i + 1]) && std::isfinite(s.y[i + 1])) {
        cv::line(plot_area, fixed(p), fixed(local.toPixel(s.x[i + 1], s.y[i + 1])), s.color, 2, cv::LINE_AA, shift);
      }
      if (s.points) cv::circle(plot_area, fixed(p), 3 << shift, s.color, cv::FILLED, cv::LINE_AA, shift);
    }
  }
  if (std::isfinite(options.marked_x)) {
    const int px = cvRound(local.toPixel(options.marked_x, 0).x);
    for (int y = 0; y < local.area.height; y += 10) {
      cv::line(plot_area, {px, y}, {px, std::min(y + 5, local.area.height - 1)}, kMarkerColor, 1);
    }
    if (std::isfinite(options.marked_y)) {
      cv::circle(plot_area, fixed(local.toPixel(options.marked_x, options.marked_y)), 6 << shift, kMarkerColor, 2,
                 cv::LINE_AA, shift);
    }
  }
  return any_missing;
}

// Legend, top right inside the plot area.
void drawLegend(cv::Mat& img, const Axes& axes, const std::vector<Series>& series, const Options& options,
                bool any_missing) {
  const double scale = fontScale(options);
  std::vector<std::pair<std::string, cv::Scalar>> legend;
  for (const auto& s : series) {
    if (!s.label.empty()) legend.emplace_back(s.label, s.color);
  }
  if (!options.marked_label.empty() && std::isfinite(options.marked_x)) legend.emplace_back(options.marked_label, kMarkerColor);
  if (any_missing) legend.emplace_back("x: no value", kMissingColor);
  int ly = axes.area.y + static_cast<int>(18 * scale / 0.45);
  for (const auto& [label, color] : legend) {
    text(img, label, {axes.area.br().x - 8, ly}, scale, color, 1);
    ly += static_cast<int>(18 * scale / 0.45);
  }
}

}  // namespace

cv::Mat plotSeries(const std::vector<Series>& series, const Options& options, Axes* axes_out) {
  if (options.width < 160 || options.height < 120) {
    throw std::invalid_argument("plot size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                                " is below 160x120");
  }
  const Axes axes = axesFor(series, options);
  cv::Mat img(options.height, options.width, CV_8UC3, cv::Scalar(255, 255, 255));
  drawFrame(img, axes, options);
  const bool any_missing = drawData(img, axes, series, options);
  drawLegend(img, axes, series, options, any_missing);
  if (axes_out) *axes_out = axes;
  return img;
}

cv::Mat plotFeedbackTrace(const imagenets::FeedbackTrace& trace, int width, int height, Axes* axes) {
  if (trace.scores.size() != trace.values.size()) {
    throw std::invalid_argument("feedback trace of " + trace.block + "." + trace.property + ": " +
                                std::to_string(trace.values.size()) + " values but " +
                                std::to_string(trace.scores.size()) + " scores");
  }
  // The trace lists the candidates in the order tried; the curve runs along the property.
  std::vector<size_t> order(trace.values.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return trace.values[a] < trace.values[b]; });
  Series s;
  for (size_t i : order) {
    s.x.push_back(trace.values[i]);
    s.y.push_back(trace.scores[i]);
  }
  Options o;
  o.width = width;
  o.height = height;
  o.title = trace.block + "." + trace.property + " -> " + trace.score;
  o.x_label = trace.property;
  o.y_label = trace.score + (trace.maximize ? " (maximised)" : " (minimised)");
  char buf[96];
  if (trace.found) {
    o.marked_x = trace.chosen_value;
    o.marked_y = trace.chosen_score;
    std::snprintf(buf, sizeof buf, "chosen %g (score %.4g)", trace.chosen_value, trace.chosen_score);
    o.marked_label = buf;
  } else {
    o.note = "no valid candidate";
  }
  if (trace.trials < trace.candidates) {
    std::snprintf(buf, sizeof buf, "%u of %u candidates evaluated", trace.trials, trace.candidates);
    o.note += (o.note.empty() ? "" : "; ") + std::string(buf);
  }
  if (!trace.stop_reason.empty()) o.note += (o.note.empty() ? "stopped: " : "; stopped: ") + trace.stop_reason;
  return plotSeries({s}, o, axes);
}

}  // namespace plot
}  // namespace imagenets
