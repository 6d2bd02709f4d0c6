// Square marker description and detector (see marker.h).
//
// Detection: quadrilaterals from the contours of the dark regions of the thresholded image give
// rough outer corners. The threshold only decides *whether* a marker is found: every edge of the
// border (4 outer, 4 inner) is then located again on the gray image, threshold-free, as the
// crossing of the local mid-level between the dark and the bright side, at many points along the
// edge; those points are undistorted and a straight line is fitted robustly to each edge (lines
// are straight only without lens distortion); corners are line intersections. The inner area,
// rectified by the homography of the outer corners, is compared with the pattern in 4 rotations
// (confidence and orientation). The pose: IPPE on the 8 points (both solutions), each refined by
// Levenberg-Marquardt, the lower reprojection error wins.
#include "imagenets/vision/marker.h"
#include "imagenets/vision/quadrilateral.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

#include <boost/filesystem.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/yaml.h>

namespace imagenets {
namespace marker {

// ---------------------------------------------------------------- description

MarkerDescription MarkerDescription::load(const std::string& yaml_path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(yaml_path + ": cannot read marker file");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(yaml_path + ": not valid YAML: " + e.what());
  }
  if (!root.IsMap()) throw std::runtime_error(yaml_path + ": a marker file is a YAML map");
  MarkerDescription m;
  m.file = yaml_path;
  auto number = [&](const char* key, double def, bool required, double lo, double hi) {
    const YAML::Node n = root[key];
    if (!n) {
      if (required) throw std::runtime_error(yaml_path + ": missing key '" + key + "'");
      return def;
    }
    double v;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error(yaml_path + ": '" + key + "' must be a number");
    }
    if (!(v > lo && v < hi)) {
      throw std::runtime_error(yaml_path + ": '" + key + "' = " + std::to_string(v) + " is out of range (" +
                               std::to_string(lo) + ", " + std::to_string(hi) + ")");
    }
    return v;
  };
  auto text = [&](const char* key) {
    const YAML::Node n = root[key];
    if (!n.IsScalar()) throw std::runtime_error(yaml_path + ": '" + key + "' must be text");
    return n.Scalar();
  };
  m.name = root["name"] ? text("name") : boost::filesystem::path(yaml_path).stem().string();
  m.size = number("size", 0.06, true, 0.0, 10.0);
  m.border = number("border", 0.25, false, 0.0, 0.5);
  m.margin = number("margin", 0.25, false, -1e-12, 10.0);
  if (!root["pattern"]) throw std::runtime_error(yaml_path + ": missing key 'pattern'");
  const boost::filesystem::path pattern_path =
      boost::filesystem::absolute(yaml_path).parent_path() / text("pattern");
  m.pattern = cv::imread(pattern_path.string(), cv::IMREAD_GRAYSCALE);
  if (m.pattern.empty()) {
    throw std::runtime_error(yaml_path + ": 'pattern': cannot read image " + pattern_path.string());
  }
  return m;
}

std::shared_ptr<const MarkerDescription> MarkerDescription::loadCached(const std::string& yaml_path) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const MarkerDescription>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[yaml_path];
  if (!entry) entry = std::make_shared<const MarkerDescription>(load(yaml_path));
  return entry;
}

std::vector<cv::Point3d> MarkerDescription::definedPoints() const {
  const double o = size / 2, i = innerSize() / 2;
  return {{-o, o, 0}, {o, o, 0}, {o, -o, 0}, {-o, -o, 0}, {-i, i, 0}, {i, i, 0}, {i, -i, 0}, {-i, -i, 0}};
}

cv::Mat MarkerDescription::texture(double pixels_per_metre, bool with_margin) const {
  const int border_px = std::max(1, static_cast<int>(std::lround(border * size * pixels_per_metre)));
  const int inner_px = std::max(1, static_cast<int>(std::lround(innerSize() * pixels_per_metre)));
  const int margin_px = with_margin ? static_cast<int>(std::lround(margin * size * pixels_per_metre)) : 0;
  const int total = inner_px + 2 * border_px + 2 * margin_px;
  cv::Mat tex(total, total, CV_8UC1, cv::Scalar(255));
  tex(cv::Rect(margin_px, margin_px, inner_px + 2 * border_px, inner_px + 2 * border_px)).setTo(0);
  cv::Mat inner;
  const int interp = inner_px >= pattern.cols ? cv::INTER_NEAREST : cv::INTER_AREA;
  cv::resize(pattern, inner, cv::Size(inner_px, inner_px), 0, 0, interp);
  inner.copyTo(tex(cv::Rect(margin_px + border_px, margin_px + border_px, inner_px, inner_px)));
  return tex;
}

render::Plane markerPlane(const MarkerDescription& marker, const Eigen::Isometry3d& pose, double pixels_per_metre) {
  render::Plane plane;
  plane.texture = marker.texture(pixels_per_metre, true);
  // The texture's pixel grid rounds the physical sizes: keep the border where the description says
  // it is by scaling the plane to the texture (ground truth must be exact).
  const double border_px = std::lround(marker.border * marker.size * pixels_per_metre);
  const double inner_px = std::lround(marker.innerSize() * pixels_per_metre);
  const double metres_per_px = marker.size / (inner_px + 2 * border_px);
  plane.width = plane.texture.cols * metres_per_px;
  plane.height = plane.texture.rows * metres_per_px;
  plane.pose = pose;
  return plane;
}

double rotationAngle(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

// ---------------------------------------------------------------- detection

namespace {

// Undistorted normalised coordinates of pixel points.
std::vector<cv::Point2d> normalise(const std::vector<cv::Point2d>& px, const render::CameraModel& cam) {
  if (px.empty()) return {};
  std::vector<cv::Point2d> out;
  cv::undistortPoints(px, out, cv::Mat(cam.K), cam.D.empty() ? cv::Mat() : cv::Mat(cam.D), cv::noArray(),
                      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 1e-12));
  return out;
}

// Distorted pixel coordinates of normalised points.
std::vector<cv::Point2d> distort(const std::vector<cv::Point2d>& norm, const render::CameraModel& cam) {
  if (norm.empty()) return {};
  std::vector<cv::Point3d> rays;
  for (const auto& p : norm) rays.emplace_back(p.x, p.y, 1.0);
  std::vector<cv::Point2d> out;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv::Mat(cam.K),
                    cam.D.empty() ? cv::Mat() : cv::Mat(cam.D), out);
  return out;
}

inline double bilinear(const cv::Mat& img, double x, double y) {
  x = std::min(std::max(x, 0.0), img.cols - 1.001);
  y = std::min(std::max(y, 0.0), img.rows - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double fx = x - x0, fy = y - y0;
  const uchar* r0 = img.ptr<uchar>(y0);
  const uchar* r1 = img.ptr<uchar>(y0 + 1);
  return (r0[x0] * (1 - fx) + r0[x0 + 1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x0 + 1] * fx) * fy;
}

// Homogeneous line through two normalised points / intersection of two lines.
cv::Vec3d lineFrom(const cv::Vec4f& fit) {
  const cv::Vec3d p(fit[2], fit[3], 1.0), q(fit[2] + fit[0], fit[3] + fit[1], 1.0);
  return p.cross(q);
}
bool intersect(const cv::Vec3d& a, const cv::Vec3d& b, cv::Point2d* out) {
  const cv::Vec3d x = a.cross(b);
  if (std::abs(x[2]) < 1e-15) return false;
  *out = cv::Point2d(x[0] / x[2], x[1] / x[2]);
  return true;
}

// Locates the 4 edges of the quadrilateral `quad_px` (distorted pixels, clockwise) on the gray
// image and returns the refined corners in normalised coordinates. `window`: how far (pixels)
// from the current edge the edge may be. False if an edge could not be located.
bool refineQuad(const cv::Mat& gray, const render::CameraModel& cam, const std::vector<cv::Point2d>& quad_px,
                double window, std::vector<cv::Point2d>* corners_norm) {
  const double step = 0.25;
  const int n_steps = static_cast<int>(std::ceil(window / step));
  std::vector<cv::Vec3d> lines(4);
  std::vector<double> prof(2 * n_steps + 1);
  for (int k = 0; k < 4; ++k) {
    const cv::Point2d a = quad_px[k], b = quad_px[(k + 1) % 4];
    const cv::Point2d d = b - a;
    const double len = std::hypot(d.x, d.y);
    if (len < 4) return false;
    const cv::Point2d t = d / len, n(t.y, -t.x);  // n: outward normal of a clockwise quad (y down)
    const int samples = std::max(6, std::min(100, static_cast<int>(len / 1.5)));
    std::vector<cv::Point2d> edge_px;
    for (int s = 0; s < samples; ++s) {
      // Stay away from the corners: there the other edge disturbs the profile.
      const double u = 0.12 + 0.76 * (s + 0.5) / samples;
      const cv::Point2d c = a + d * u;
      // Intensity profile along the normal, averaged over a short segment along the edge.
      for (int i = -n_steps; i <= n_steps; ++i) {
        const cv::Point2d q = c + n * (i * step);
        prof[i + n_steps] = (bilinear(gray, q.x - 0.5 * t.x, q.y - 0.5 * t.y) + bilinear(gray, q.x, q.y) +
                             bilinear(gray, q.x + 0.5 * t.x, q.y + 0.5 * t.y)) / 3.0;
      }
      // Strongest gradient (either polarity: outer edges go dark -> bright outwards, inner ones
      // bright -> dark), then the mid-level crossing around it: unbiased for a symmetric blur and
      // independent of any threshold.
      int best = -1;
      double best_g = 0;
      for (int i = 1; i + 1 < static_cast<int>(prof.size()); ++i) {
        const double g = std::abs(prof[i + 1] - prof[i - 1]);
        if (g > best_g) best_g = g, best = i;
      }
      if (best < 0 || best_g < 4.0) continue;
      const int reach = static_cast<int>(std::lround(2.5 / step));
      const int lo_i = std::max(0, best - reach), hi_i = std::min(static_cast<int>(prof.size()) - 1, best + reach);
      const double side_a = prof[lo_i], side_b = prof[hi_i];
      if (std::abs(side_b - side_a) < 10.0) continue;  // too little contrast to locate the edge
      const double mid = 0.5 * (side_a + side_b);
      // Walk from the gradient peak to the crossing.
      double pos = std::numeric_limits<double>::quiet_NaN();
      for (int off = 0; off <= reach && std::isnan(pos); ++off) {
        for (int sgn : {-1, 1}) {
          const int i = best + sgn * off;
          if (i < lo_i || i + 1 > hi_i) continue;
          const double v0 = prof[i] - mid, v1 = prof[i + 1] - mid;
          if ((v0 <= 0 && v1 > 0) || (v0 >= 0 && v1 < 0)) {
            pos = (i + v0 / (v0 - v1) - n_steps) * step;
            break;
          }
        }
      }
      if (std::isnan(pos)) continue;
      edge_px.push_back(c + n * pos);
    }
    if (edge_px.size() < 4) return false;
    const std::vector<cv::Point2d> edge_norm = normalise(edge_px, cam);
    std::vector<cv::Point2f> pts(edge_norm.begin(), edge_norm.end());
    cv::Vec4f fit;
    // Least squares. cv::fitLine's DIST_HUBER is no Huber fit here: its constant (1.345) is in the
    // points' units, normalised coordinates, far above every residual; what it did was fit 20
    // random 10-point subsets and keep the line with the least sum of distances, at 20x the cost
    // and less accurately (bench_calibration_detection, clean views: 0.050 -> 0.041 mm mean).
    cv::fitLine(pts, fit, cv::DIST_L2, 0, 0, 0);
    lines[k] = lineFrom(fit);
  }
  corners_norm->resize(4);
  for (int k = 0; k < 4; ++k) {
    if (!intersect(lines[(k + 3) % 4], lines[k], &(*corners_norm)[k])) return false;
  }
  return true;
}

// The pixels of the band within `half_band` px of the edge from a to b (normalised), the middle
// 70 % of it: their undistorted positions `q` and gray values `v`. `n0`, `c`: the edge's line
// (n0 . q = c); `f`: focal length, normalised -> pixels. False if the band is empty or too large.
bool edgeBandPixels(const cv::Mat& gray, const render::CameraModel& cam, const cv::Point2d& a, const cv::Point2d& b,
                    const cv::Point2d& n0, double c, double f, double half_band, std::vector<cv::Point2d>* q,
                    std::vector<double>* v) {
  // Candidate pixels: the box around the segment, widened by the band.
  const std::vector<cv::Point2d> ends = distort({a, b}, cam);
  const double pad = half_band + 2;
  const int x0 = std::max(1, static_cast<int>(std::floor(std::min(ends[0].x, ends[1].x) - pad)));
  const int x1 = std::min(gray.cols - 2, static_cast<int>(std::ceil(std::max(ends[0].x, ends[1].x) + pad)));
  const int y0 = std::max(1, static_cast<int>(std::floor(std::min(ends[0].y, ends[1].y) - pad)));
  const int y1 = std::min(gray.rows - 2, static_cast<int>(std::ceil(std::max(ends[0].y, ends[1].y) + pad)));
  if (x1 <= x0 || y1 <= y0 || (x1 - x0) * (y1 - y0) > 200000) return false;
  // Only pixels near the edge in the image are undistorted (the costly step): the distorted edge
  // is straight to well within the margin `pad` leaves over the band.
  const cv::Point2d e = ends[1] - ends[0];
  const double e_len = cv::norm(e);
  if (e_len < 4) return false;
  const cv::Point2d et = e / e_len, en(et.y, -et.x);
  std::vector<cv::Point2d> px;
  std::vector<double> value;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const cv::Point2d r = cv::Point2d(x, y) - ends[0];
      const double along = r.dot(et) / e_len;
      if (std::abs(r.dot(en)) > pad || along < 0.1 || along > 0.9) continue;
      px.emplace_back(x, y), value.push_back(gray.at<uchar>(y, x));
    }
  }
  const std::vector<cv::Point2d> q_all = normalise(px, cam);
  const double len = cv::norm(b - a);
  const cv::Point2d t = (b - a) / len;
  for (size_t i = 0; i < q_all.size(); ++i) {
    const double u = (q_all[i] - a).dot(t) / len;
    const double d = f * (n0.dot(q_all[i]) - c);
    if (u > 0.15 && u < 0.85 && std::abs(d) <= half_band) q->push_back(q_all[i]), v->push_back(value[i]);
  }
  return true;
}

// The blurred step edge's parameters: the line n(theta) . q = c, the mid-level m, the half step h
// and the blur s (pixels).
struct EdgeModel {
  double theta, c, m, h, s;
};

// Fits `model` to the band's pixels (q, v) by Gauss-Newton with Huber weights, the threshold from
// the residuals' robust spread. A saturated pixel (over-exposed paper) only says the model is at
// least as bright: clipping would otherwise pull the edge towards the dark side. `line_scale`:
// pixels the line's end moves per radian (convergence test). False if a step is not finite.
bool fitEdgeModel(const std::vector<cv::Point2d>& q, const std::vector<double>& v, double f, double line_scale,
                  EdgeModel* model) {
  double& theta = model->theta;
  double& c = model->c;
  double& m = model->m;
  double& h = model->h;
  double& s = model->s;
  double lambda = 1e-3;
  auto residual = [](double value, double model) { return value >= 254.5 ? std::min(0.0, value - model) : value - model; };
  auto huberCost = [](double r, double k) {
    r = std::abs(r);
    return r <= k ? r * r : 2 * k * r - k * k;
  };
  auto cost = [&](double th, double cc, double mm, double hh, double ss, double k) {
    double sum = 0;
    const cv::Point2d n(std::cos(th), std::sin(th));
    for (size_t i = 0; i < q.size(); ++i) {
      sum += huberCost(residual(v[i], mm + hh * std::erf(f * (n.dot(q[i]) - cc) / (M_SQRT2 * ss))), k);
    }
    return sum;
  };
  for (int iter = 0; iter < 30; ++iter) {
    const cv::Point2d n(std::cos(theta), std::sin(theta)), dn(-std::sin(theta), std::cos(theta));
    std::vector<double> abs_r(q.size());
    for (size_t i = 0; i < q.size(); ++i) {
      abs_r[i] = std::abs(residual(v[i], m + h * std::erf(f * (n.dot(q[i]) - c) / (M_SQRT2 * s))));
    }
    std::vector<double> sorted_r = abs_r;
    std::nth_element(sorted_r.begin(), sorted_r.begin() + sorted_r.size() / 2, sorted_r.end());
    const double huber = std::max(1.0, 2.0 * 1.4826 * sorted_r[sorted_r.size() / 2]);
    double before = 0;  // the cost at the current parameters, from the residuals just computed
    for (const double r : abs_r) before += huberCost(r, huber);
    Eigen::Matrix<double, 5, 5> JtJ = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> Jtr = Eigen::Matrix<double, 5, 1>::Zero();
    for (size_t i = 0; i < q.size(); ++i) {
      const double d = f * (n.dot(q[i]) - c), z = d / (M_SQRT2 * s);
      const double e = std::erf(z), g = h * M_2_SQRTPI * std::exp(-z * z) / (M_SQRT2 * s);  // dI/dd
      const double r = residual(v[i], m + h * e);
      if (v[i] >= 254.5 && r == 0) continue;  // saturated and the model bright enough: no information
      const double w = std::abs(r) <= huber ? 1.0 : huber / std::abs(r);
      Eigen::Matrix<double, 5, 1> J;
      J << g * f * dn.dot(q[i]), -g * f, 1.0, e, -g * d / s;  // d model / d (theta, c, m, h, s)
      JtJ += w * J * J.transpose();
      Jtr += w * J * r;
    }
    bool improved = false;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Eigen::Matrix<double, 5, 5> A = JtJ;
      A.diagonal() *= 1 + lambda;
      const Eigen::Matrix<double, 5, 1> dx = A.ldlt().solve(Jtr);
      if (!dx.allFinite()) return false;
      const double s_new = std::max(0.2, s + dx(4));
      if (cost(theta + dx(0), c + dx(1), m + dx(2), h + dx(3), s_new, huber) < before) {
        theta += dx(0), c += dx(1), m += dx(2), h += dx(3), s = s_new;
        lambda = std::max(1e-6, lambda / 4);
        improved = true;
        // Converged once the line moves by less than a thousandth of a pixel.
        if (f * (std::abs(dx(1)) + std::abs(dx(0)) * line_scale) < 1e-3) iter = 30;
      } else {
        lambda *= 8;
      }
    }
    if (!improved) break;
  }
  return true;
}

// Fits a blurred straight step edge, I = m + h erf(d / (sqrt(2) s)) with d the pixel's signed
// distance to the line, to every pixel within `half_band` px of the edge from a to b (normalised,
// the middle 70 % of it), by Gauss-Newton with Huber weights. Every pixel of the band counts, not
// one crossing per profile: in dim, noisy images that is what locates the edge. The model is
// symmetric about the line, so blur does not shift it. False if the fit does not settle.
bool fitBlurredEdge(const cv::Mat& gray, const render::CameraModel& cam, const cv::Point2d& a, const cv::Point2d& b,
                    double half_band, cv::Vec3d* line, int* saturated) {
  const double f = 0.5 * (cam.K(0, 0) + cam.K(1, 1));
  const cv::Point2d t = (b - a) / cv::norm(b - a);
  EdgeModel model;
  model.theta = std::atan2(-t.x, t.y);
  const cv::Point2d n0(std::cos(model.theta), std::sin(model.theta));  // the starting line's normal
  model.c = n0.dot(a);
  std::vector<cv::Point2d> q;
  std::vector<double> v;
  if (!edgeBandPixels(gray, cam, a, b, n0, model.c, f, half_band, &q, &v) || q.size() < 20) return false;
  *saturated = static_cast<int>(std::count_if(v.begin(), v.end(), [](double x) { return x >= 254.5; }));
  // Start: the two sides' means, a 1 px blur.
  double lo = 0, hi = 0;
  int n_lo = 0, n_hi = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const double d = f * (n0.dot(q[i]) - model.c);
    if (d < 0) lo += v[i], ++n_lo;
    else hi += v[i], ++n_hi;
  }
  if (n_lo < 5 || n_hi < 5) return false;
  model.m = 0.5 * (lo / n_lo + hi / n_hi), model.h = 0.5 * (hi / n_hi - lo / n_lo), model.s = 1.0;
  if (std::abs(model.h) < 3) return false;
  const cv::Point2d mid = 0.5 * (a + b);
  if (!fitEdgeModel(q, v, f, cv::norm(mid) + cv::norm(b - a), &model)) return false;
  // Settled near where it started, with a plausible blur: otherwise keep the profile estimate.
  const double moved = f * std::abs(cv::Point2d(std::cos(model.theta), std::sin(model.theta)).dot(mid) - model.c);
  if (!(model.s > 0.2 && model.s < 6 && moved < 1.5 && std::abs(model.h) >= 3)) return false;
  *line = cv::Vec3d(std::cos(model.theta), std::sin(model.theta), -model.c);
  return true;
}

// The outer corners again from the edge model of each side (fitBlurredEdge). The band stays
// inside the black border and the white margin. Unchanged and false if any side does not fit;
// `clipped`: the white paper is over-exposed along the edges (over 5 % of the band saturated).
bool fitOuterEdges(const cv::Mat& gray, const render::CameraModel& cam, std::vector<cv::Point2d>* corners_norm,
                   bool* clipped) {
  const std::vector<cv::Point2d> px = distort(*corners_norm, cam);
  std::vector<cv::Vec3d> lines(4);
  int saturated = 0, pixels = 0;
  for (int k = 0; k < 4; ++k) {
    const double side_px = cv::norm(px[k] - px[(k + 1) % 4]);
    const double half_band = std::min(5.0, 0.2 * side_px);
    int n_saturated = 0;
    if (half_band < 1.5) return false;
    if (!fitBlurredEdge(gray, cam, (*corners_norm)[k], (*corners_norm)[(k + 1) % 4], half_band, &lines[k], &n_saturated)) {
      return false;
    }
    saturated += n_saturated;
    pixels += static_cast<int>(2 * half_band * 0.7 * side_px);
  }
  std::vector<cv::Point2d> out(4);
  for (int k = 0; k < 4; ++k) {
    if (!intersect(lines[(k + 3) % 4], lines[k], &out[k])) return false;
  }
  *corners_norm = out;
  *clipped = saturated > 0.05 * pixels;
  return true;
}

double zeroMeanNcc(const cv::Mat& a, const cv::Mat& b) {
  cv::Scalar ma, sa, mb, sb;
  cv::meanStdDev(a, ma, sa);
  cv::meanStdDev(b, mb, sb);
  if (sa[0] < 1e-6 || sb[0] < 1e-6) return 0.0;
  cv::Mat a0, b0;
  a.convertTo(a0, CV_64F, 1.0, -ma[0]);
  b.convertTo(b0, CV_64F, 1.0, -mb[0]);
  return a0.dot(b0) / (a.total() * sa[0] * sb[0]);
}

struct Candidate {
  std::vector<cv::Point2d> outer_norm;  // clockwise, image corner order
  double confidence = 0;
  int rotation = 0;
};

// The blurred match is tried only on markers with a side shorter than this (pixels): blur smears
// cells into each other only where the marker is narrow in the image (far, or seen steeply). The
// far views it was made for have sides of 20..60 px; on a close marker a reflection spoils, it
// would cost a few milliseconds at every threshold tried.
constexpr double kBlurMattersBelowPx = 80;

// The shortest and the longest side of a quadrilateral (pixels).
std::pair<double, double> sideRange(const std::vector<cv::Point2d>& quad) {
  std::pair<double, double> range(std::numeric_limits<double>::infinity(), 0.0);
  for (size_t k = 0; k < quad.size(); ++k) {
    const double side = cv::norm(quad[k] - quad[(k + 1) % quad.size()]);
    range = {std::min(range.first, side), std::max(range.second, side)};
  }
  return range;
}
// A blurred match counts from this confidence on, even where the sharp one needs less: the marker
// matches at >= 0.83, other patterns at up to 0.59 (random ones <= 0.55), and other dark
// quadrilaterals of the calibration's scenes at 0.60 (docs/markers.md).
constexpr double kBlurredMatchMinConfidence = 0.7;

// What the blurred match compares the samples with: the marker (border, pattern, margin) at
// kTextureSide px across its black square, and where that square starts in the texture.
struct MatchTexture {
  static constexpr double kTextureSide = 96;
  cv::Mat texture;  // CV_8UC1
  double origin = 0;
  explicit MatchTexture(const MarkerDescription& marker)
      : texture(marker.texture(kTextureSide / marker.size, true)),
        origin(std::lround(marker.margin * marker.size * (kTextureSide / marker.size))) {}
};

// The expected gray values at the sample points `norm` (normalised) of the marker seen through the
// homography H (unit square -> normalised) with each image-space Gaussian blur of `sigmas_px`
// (ascending), for each of the 4 quarter turns of the texture. Empty when the marker is too large
// for the patch.
std::vector<std::vector<cv::Mat>> blurredExpectations(const MatchTexture& match, const render::CameraModel& cam,
                                                      const cv::Mat& H, const std::vector<cv::Point2d>& norm,
                                                      const std::vector<double>& sigmas_px, int cells) {
  // Undistorted pixels: blur is a few pixels, the distortion over a small marker negligible.
  const cv::Matx33d KH = cam.K * cv::Matx33d(H);
  std::vector<cv::Point2f> corners_px;
  for (const cv::Point2d u : {cv::Point2d(-0.3, -0.3), {1.3, -0.3}, {1.3, 1.3}, {-0.3, 1.3}}) {
    const cv::Vec3d p = KH * cv::Vec3d(u.x, u.y, 1.0);
    if (!(p[2] > 0)) return {};
    corners_px.emplace_back(p[0] / p[2], p[1] / p[2]);
  }
  const double max_sigma = *std::max_element(sigmas_px.begin(), sigmas_px.end());
  const cv::Rect2d box = cv::boundingRect(corners_px);
  const double pad = 3 * max_sigma + 2, side = std::max(box.width, box.height) + 2 * pad;
  if (side > 400) return {};  // cells of many pixels: the sharp match is right
  const double k = std::max(1.0, std::min(4.0, 96.0 / side));  // supersampling of the rendered patch
  const int size = static_cast<int>(std::ceil(side * k));
  // texture px -> unit square -> normalised -> pixels -> patch
  const double t = MatchTexture::kTextureSide, o = match.origin;
  const cv::Matx33d tex_to_unit(1 / t, 0, -o / t, 0, 1 / t, -o / t, 0, 0, 1);
  const cv::Matx33d px_to_patch(k, 0, -k * (box.x - pad), 0, k, -k * (box.y - pad), 0, 0, 1);
  const cv::Matx33d M = px_to_patch * KH * tex_to_unit;
  std::vector<cv::Point2d> at;
  for (const auto& q : norm) {
    const cv::Vec3d p = cam.K * cv::Vec3d(q.x, q.y, 1.0);
    at.emplace_back(k * (p[0] / p[2] - box.x + pad), k * (p[1] / p[2] - box.y + pad));
  }
  std::vector<double> sorted(sigmas_px);
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::vector<cv::Mat>> out(sorted.size());  // [blur][quarter turn]
  cv::Mat turned = match.texture;
  for (int r = 0; r < 4; ++r) {
    cv::Mat patch;
    cv::warpPerspective(turned, patch, cv::Mat(M), cv::Size(size, size), cv::INTER_AREA, cv::BORDER_CONSTANT,
                        cv::Scalar(255));
    double done = 0;  // blur already applied: each larger one adds only what is missing
    for (size_t j = 0; j < sorted.size(); ++j) {
      cv::GaussianBlur(patch, patch, cv::Size(0, 0), k * std::sqrt(sorted[j] * sorted[j] - done * done));
      done = sorted[j];
      cv::Mat expected(cells, cells, CV_64F);
      for (int i = 0; i < cells * cells; ++i) expected.at<double>(i / cells, i % cells) = bilinear(patch, at[i].x, at[i].y);
      out[j].push_back(expected);
    }
    cv::rotate(turned, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  }
  return out;
}

// Rectifies the inner area through the homography of the outer corners and matches the pattern.
// With `blurred`, against the pattern as a camera blurring by each of `blurs` (px) shows it
// instead (far, small markers: every cell a pixel or two, smeared into its neighbours).
void matchPattern(const cv::Mat& gray, const render::CameraModel& cam, const MarkerDescription& marker,
                  const cv::Mat& pattern_cells, int cells, const MatchTexture* blurred,
                  const std::vector<double>& blurs, Candidate* cand) {
  // Marker-plane square [0,1]^2 (u right, v down as in the pattern image) onto the image quad.
  const std::vector<cv::Point2f> unit{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<cv::Point2f> quad(cand->outer_norm.begin(), cand->outer_norm.end());
  const cv::Mat H = cv::getPerspectiveTransform(unit, quad);
  const double b = marker.border;
  std::vector<cv::Point2d> plane, norm;
  for (int r = 0; r < cells; ++r) {
    for (int c = 0; c < cells; ++c) {
      plane.emplace_back(b + (1 - 2 * b) * (c + 0.5) / cells, b + (1 - 2 * b) * (r + 0.5) / cells);
    }
  }
  cv::perspectiveTransform(plane, norm, H);
  const std::vector<cv::Point2d> px = distort(norm, cam);
  cv::Mat patch(cells, cells, CV_64F);
  for (int i = 0; i < cells * cells; ++i) patch.at<double>(i / cells, i % cells) = bilinear(gray, px[i].x, px[i].y);
  cand->confidence = -1;
  if (blurred) {
    for (const auto& per_blur : blurredExpectations(*blurred, cam, H, norm, blurs, cells)) {
      for (size_t k = 0; k < per_blur.size(); ++k) {
        const double ncc = zeroMeanNcc(patch, per_blur[k]);
        if (ncc > cand->confidence) cand->confidence = ncc, cand->rotation = static_cast<int>(k);
      }
    }
  } else {
    cv::Mat rotated = patch;
    for (int k = 0; k < 4; ++k) {
      const double ncc = zeroMeanNcc(rotated, pattern_cells);
      if (ncc > cand->confidence) cand->confidence = ncc, cand->rotation = k;
      cv::rotate(rotated, rotated, cv::ROTATE_90_CLOCKWISE);
    }
  }
  cand->confidence = std::max(0.0, std::min(1.0, cand->confidence));
}

Eigen::Isometry3d toIsometry(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = R(r, c);
    T.translation()(r) = tvec[r];
  }
  return T;
}

}  // namespace

bool refineSquareEdges(const cv::Mat& gray, const render::CameraModel& camera, const std::vector<cv::Point2d>& quad_px,
                       int passes, std::vector<cv::Point2d>* refined_px) {
  if (quad_px.size() != 4) return false;
  std::vector<cv::Point2d> px = quad_px, norm;
  for (int pass = 0; pass < passes; ++pass) {
    if (!refineQuad(gray, camera, px, pass == 0 ? 4.0 : 2.5, &norm)) return false;
    px = distort(norm, camera);
  }
  *refined_px = px;
  return true;
}

namespace {

void checkDetectInputs(const cv::Mat& gray, const cv::Mat& binary, const render::CameraModel& camera,
                       const MarkerDescription& marker) {
  if (gray.empty() || gray.type() != CV_8UC1) throw std::invalid_argument("gray image must be a non-empty mono8 image");
  if (binary.type() != CV_8UC1 || binary.size() != gray.size()) {
    throw std::invalid_argument("thresholded image must be mono8 and of the gray image's size");
  }
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw std::invalid_argument("image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                                " but camera_info says " + std::to_string(camera.width) + "x" +
                                std::to_string(camera.height));
  }
  if (marker.pattern.empty()) throw std::invalid_argument("marker '" + marker.name + "' has no pattern");
}

// Where the pose hint puts the marker's outer corners in the image; empty without a hint or with
// the marker behind the camera.
std::vector<cv::Point2d> hintedOuterCorners(const render::CameraModel& camera, const MarkerDescription& marker,
                                            const DetectorOptions& options) {
  std::vector<cv::Point2d> outer;
  if (!options.pose_hint) return outer;
  const std::vector<cv::Point3d> defined = marker.definedPoints();
  for (int j = 0; j < 4; ++j) {
    const Eigen::Vector3d p = *options.pose_hint * Eigen::Vector3d(defined[j].x, defined[j].y, defined[j].z);
    if (p.z() <= 0) return {};
    outer.push_back(camera.project(p));
  }
  return outer;
}

// How finely the dark regions are traced: options.decimate, unless the pose hint says the marker's
// border is narrow in the image (under kMinDecimatedBorderPx at that scale: far, or seen steeply).
constexpr double kMinDecimatedBorderPx = 3;
int decimation(const std::vector<cv::Point2d>& hinted, const MarkerDescription& marker, const DetectorOptions& options) {
  const int d = std::max(1, options.decimate);
  if (d == 1 || !options.pose_hint) return d;
  if (hinted.empty()) return 1;
  // The border's narrowest width: the quadrilateral's (a parallelogram's area over its longest
  // side), scaled by the border's share of the marker; a steep view narrows it in any direction.
  const double area = std::abs(cv::contourArea(std::vector<cv::Point2f>(hinted.begin(), hinted.end())));
  return area / sideRange(hinted).second * marker.border >= kMinDecimatedBorderPx * d ? d : 1;
}

// The shortest side (px) a quadrilateral must have to be examined.
double minSidePx(const std::vector<cv::Point2d>& hinted, const DetectorOptions& options) {
  if (hinted.empty() || options.min_side_of_hint <= 0) return options.min_side_px;
  return std::max(options.min_side_px, options.min_side_of_hint * sideRange(hinted).first);
}

// The candidate that matches the pattern best: every dark region's outline that approximates a
// convex quadrilateral, its edges located on the gray image, its inner area matched; when none
// matches the sharp pattern, those that looked a little like it matched again, blurred.
// `candidates`: how many quadrilaterals were examined.
Candidate bestCandidate(const cv::Mat& gray, const cv::Mat& binary, const render::CameraModel& camera,
                        const MarkerDescription& marker, const DetectorOptions& options, int* candidates) {
  cv::Mat pattern_cells;
  cv::resize(marker.pattern, pattern_cells, cv::Size(options.pattern_cells, options.pattern_cells), 0, 0,
             cv::INTER_AREA);
  pattern_cells.convertTo(pattern_cells, CV_64F);

  // Dark regions (the border is below the threshold) and their outer boundaries; with `decimate`,
  // of every d-th pixel of every d-th row (the rough corners are refined on the gray image anyway).
  const std::vector<cv::Point2d> hinted = hintedOuterCorners(camera, marker, options);
  const int d = decimation(hinted, marker, options);
  const double min_side_px = minSidePx(hinted, options);
  cv::Mat dark;
  if (d > 1) {
    dark.create((binary.rows + d - 1) / d, (binary.cols + d - 1) / d, CV_8UC1);
    for (int y = 0; y < dark.rows; ++y) {
      const uchar* in = binary.ptr<uchar>(y * d);
      uchar* out = dark.ptr<uchar>(y);
      for (int x = 0; x < dark.cols; ++x) out[x] = in[x * d] == 0 ? 255 : 0;
    }
  } else {
    dark = binary == 0;
  }
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(dark, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);

  Candidate best;
  best.confidence = -1;
  std::vector<Candidate> rescuable;
  const cv::Rect2f inside(3.0f / d, 3.0f / d, (gray.cols - 6.0f) / d, (gray.rows - 6.0f) / d);
  for (size_t ci = 0; ci < contours.size(); ++ci) {
    if (hierarchy[ci][3] >= 0) continue;  // a hole's boundary, not a region's outline
    const auto corners = convexQuadrilateral(contours[ci], 0.05, min_side_px / d, inside);
    if (!corners) continue;
    ++*candidates;
    std::vector<cv::Point2d> quad;
    for (const cv::Point2f& c : *corners) quad.emplace_back(c.x * d, c.y * d);

    Candidate cand;
    std::vector<cv::Point2d> outer_px = quad;
    bool refined = true;
    for (int pass = 0; pass < options.refine_passes && refined; ++pass) {
      refined = refineQuad(gray, camera, outer_px, pass == 0 ? 4.0 : 2.5, &cand.outer_norm);
      if (refined) outer_px = distort(cand.outer_norm, camera);
      // Most quadrilaterals are something else (a part of the robot, a shadow): once located
      // roughly, one whose pattern does not look like the marker's at all (< 0.1, where another
      // pattern matches ~0.1, the marker >= 0.83) is dropped before the finer passes. Not those
      // the blurred match may still take, whose sharp match is low anyway.
      if (refined && pass == 0 && options.refine_passes > 1 &&
          (options.match_blur_px.empty() || sideRange(outer_px).first >= kBlurMattersBelowPx)) {
        matchPattern(gray, camera, marker, pattern_cells, options.pattern_cells, nullptr, {}, &cand);
        if (cand.confidence < 0.1) refined = false;
      }
    }
    if (!refined) continue;
    // The limit holds for the located square too: a speck whose contour passed it can shrink to
    // a few pixels, and a few pixels match a blurred pattern about as well as anything.
    const double shortest_px = sideRange(outer_px).first;
    if (shortest_px < min_side_px) continue;
    if (options.refine_passes == 0) cand.outer_norm = normalise(outer_px, camera);
    matchPattern(gray, camera, marker, pattern_cells, options.pattern_cells, nullptr, {}, &cand);
    if (cand.confidence > best.confidence) best = cand;
    // Below 0.1 a candidate does not look like the marker at all (another pattern matches ~0.1).
    if (!options.match_blur_px.empty() && cand.confidence > 0.1 && shortest_px < kBlurMattersBelowPx) {
      rescuable.push_back(cand);
    }
  }
  if (best.confidence < options.min_confidence && !rescuable.empty()) {
    const MatchTexture blurred(marker);
    const double blurred_min = std::max(options.min_confidence, kBlurredMatchMinConfidence);
    for (size_t i = 0; best.confidence < options.min_confidence && i < rescuable.size(); ++i) {
      Candidate& cand = rescuable[i];
      matchPattern(gray, camera, marker, pattern_cells, options.pattern_cells, &blurred, options.match_blur_px, &cand);
      if (cand.confidence >= blurred_min && cand.confidence > best.confidence) best = cand;
    }
  }
  return best;
}

// The inner corners (normalised): from the homography of the outer ones (`outer`, in marker
// order), their edges then located too. `inner_side_px`: the shortest side of the inner square in
// the image. False if an edge could not be located (the homography's corners are kept).
bool innerCorners(const cv::Mat& gray, const render::CameraModel& camera, const MarkerDescription& marker,
                  const std::vector<cv::Point2d>& outer, int refine_passes, std::vector<cv::Point2d>* inner_norm,
                  double* inner_side_px) {
  const std::vector<cv::Point3d> defined = marker.definedPoints();
  std::vector<cv::Point2f> plane_outer, img_outer(outer.begin(), outer.end());
  for (int j = 0; j < 4; ++j) plane_outer.emplace_back(defined[j].x, defined[j].y);
  const cv::Mat H = cv::getPerspectiveTransform(plane_outer, img_outer);
  std::vector<cv::Point2d> plane_inner;
  for (int j = 4; j < 8; ++j) plane_inner.emplace_back(defined[j].x, defined[j].y);
  cv::perspectiveTransform(plane_inner, *inner_norm, H);
  bool refined = true;
  std::vector<cv::Point2d> inner_px = distort(*inner_norm, camera), refined_inner;
  for (int pass = 0; pass < refine_passes && refined; ++pass) {
    refined = refineQuad(gray, camera, inner_px, pass == 0 ? 2.5 : 1.5, &refined_inner);
    if (refined) inner_px = distort(refined_inner, camera), *inner_norm = refined_inner;
  }
  *inner_side_px = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) *inner_side_px = std::min(*inner_side_px, cv::norm(inner_px[k] - inner_px[(k + 1) % 4]));
  return refined;
}

// The pose from the 8 points (`image_norm`: outer then inner corners, normalised; the inner ones
// repeated `inner_weight` times in the fit when `use_inner`): IPPE's solutions, each refined by
// Levenberg-Marquardt; the lower RMS reprojection error wins, or, when both fit about equally well,
// the one closer to the hint. False if IPPE gives none.
bool fitPose(const MarkerDescription& marker, const std::vector<cv::Point2d>& image_norm, bool use_inner,
             const DetectorOptions& options, double focal_px, Detection* result) {
  const std::vector<cv::Point3d> defined = marker.definedPoints();
  std::vector<cv::Point3d> fit_object(defined.begin(), defined.begin() + 4);
  std::vector<cv::Point2d> fit_image(image_norm.begin(), image_norm.begin() + 4);
  for (int w = 0; use_inner && w < std::max(1, options.inner_weight); ++w) {
    fit_object.insert(fit_object.end(), defined.begin() + 4, defined.end());
    fit_image.insert(fit_image.end(), image_norm.begin() + 4, image_norm.end());
  }
  const cv::Mat I = cv::Mat::eye(3, 3, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  const int n = cv::solvePnPGeneric(fit_object, fit_image, I, cv::noArray(), rvecs, tvecs, false, cv::SOLVEPNP_IPPE);
  if (n == 0) return false;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<double> errors;
  for (int s = 0; s < n; ++s) {
    cv::Mat rvec = rvecs[s].clone(), tvec = tvecs[s].clone();
    cv::solvePnPRefineLM(fit_object, fit_image, I, cv::noArray(), rvec, tvec,
                         cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-12));
    // RMS over the points of the fit (each once): the outer corners alone when the inner ones were left out.
    const std::vector<cv::Point3d> fitted(defined.begin(), defined.begin() + (use_inner ? 8 : 4));
    std::vector<cv::Point2d> reproj;
    cv::projectPoints(fitted, rvec, tvec, I, cv::noArray(), reproj);
    double sq = 0;
    for (size_t i = 0; i < reproj.size(); ++i) {
      const cv::Point2d e = reproj[i] - image_norm[i];
      sq += e.dot(e);
    }
    poses.push_back(toIsometry(cv::Vec3d(rvec), cv::Vec3d(tvec)));
    errors.push_back(focal_px * std::sqrt(sq / reproj.size()));
  }
  int chosen = 0;
  if (n > 1) {
    chosen = errors[1] < errors[0] ? 1 : 0;
    const double lo = std::min(errors[0], errors[1]), hi = std::max(errors[0], errors[1]);
    if (options.pose_hint && hi < options.ambiguity_ratio * std::max(lo, 1e-9)) {
      // Ambiguous: keep the solution whose orientation is closer to the hint (temporal consistency).
      chosen = rotationAngle(poses[0], *options.pose_hint) <= rotationAngle(poses[1], *options.pose_hint) ? 0 : 1;
    }
  }
  result->pose = poses[chosen];
  result->reprojection_error = errors[chosen];
  result->alt_pose = n > 1 ? poses[1 - chosen] : poses[chosen];
  result->alt_reprojection_error = n > 1 ? errors[1 - chosen] : errors[chosen];
  return true;
}

}  // namespace

Detection detect(const cv::Mat& gray, const cv::Mat& binary, const render::CameraModel& camera,
                 const MarkerDescription& marker, const DetectorOptions& options) {
  checkDetectInputs(gray, binary, camera, marker);
  Detection result;
  Candidate best = bestCandidate(gray, binary, camera, marker, options, &result.candidates);
  if (best.confidence < options.min_confidence || best.outer_norm.empty()) {
    result.confidence = std::max(0.0, best.confidence);
    return result;
  }

  // With the edge model the outer corners alone give the better pose, except on over-exposed
  // paper, where the inner corners' opposite shift cancels the outer ones' (inner_weight).
  bool clipped = false;
  const bool small =
      options.edge_model_max_side_px <= 0 || sideRange(distort(best.outer_norm, camera)).second < options.edge_model_max_side_px;
  const bool edge_fitted = options.edge_model && small && options.refine_passes > 0 &&
                           fitOuterEdges(gray, camera, &best.outer_norm, &clipped);

  // Put the corners in marker order: after k clockwise quarter turns of the rectified patch the
  // marker's top-left corner is image corner (4 - k) % 4.
  std::vector<cv::Point2d> outer(4);
  for (int j = 0; j < 4; ++j) outer[j] = best.outer_norm[(j - best.rotation + 8) % 4];

  std::vector<cv::Point2d> inner_norm;
  double inner_side_px = 0;
  const bool inner_refined = innerCorners(gray, camera, marker, outer, options.refine_passes, &inner_norm, &inner_side_px);
  // A small inner square (far away, seen steeply) lies among the pattern's cells: its blurred edges
  // have no bright plateau and its corners are off by up to a pixel. Then only the outer corners fit.
  const bool use_inner =
      (options.min_inner_side_px <= 0 || (inner_refined && inner_side_px >= options.min_inner_side_px)) &&
      (!edge_fitted || clipped);

  std::vector<cv::Point2d> image_norm(outer);
  image_norm.insert(image_norm.end(), inner_norm.begin(), inner_norm.end());
  const double f = 0.5 * (camera.K(0, 0) + camera.K(1, 1));  // normalised -> pixel error scale
  if (!fitPose(marker, image_norm, use_inner, options, f, &result)) return result;
  result.found = true;
  result.confidence = best.confidence;
  result.rotation = best.rotation;
  const std::vector<cv::Point2d> px = distort(image_norm, camera);
  for (int i = 0; i < 8; ++i) result.points[i] = px[i];
  return result;
}

}  // namespace marker
}  // namespace imagenets
