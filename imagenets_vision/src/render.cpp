// Ray-casting renderer of textured planes (see render.h for the model and conventions).
#include "imagenets/vision/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>

namespace imagenets {
namespace render {

CameraModel CameraModel::fromCameraInfo(const sensor_msgs::CameraInfo& info) {
  CameraModel cam;
  if (info.width == 0 || info.height == 0) {
    throw std::invalid_argument("camera_info has zero image size (" + std::to_string(info.width) + "x" +
                                std::to_string(info.height) + ")");
  }
  cam.width = static_cast<int>(info.width);
  cam.height = static_cast<int>(info.height);
  for (int i = 0; i < 9; ++i) cam.K.val[i] = info.K[i];
  if (!(cam.K(0, 0) > 0) || !(cam.K(1, 1) > 0) || std::abs(cam.K(2, 2) - 1.0) > 1e-9) {
    throw std::invalid_argument("camera_info K is not a valid camera matrix (fx, fy > 0, K[8] = 1)");
  }
  const std::string& model = info.distortion_model;
  if (!info.D.empty() && model != "plumb_bob" && model != "rational_polynomial") {
    throw std::invalid_argument("camera_info distortion_model '" + model +
                                "' is not supported (plumb_bob or rational_polynomial)");
  }
  cam.D.assign(info.D.begin(), info.D.end());
  if (std::all_of(cam.D.begin(), cam.D.end(), [](double d) { return d == 0.0; })) cam.D.clear();
  return cam;
}

cv::Point2d CameraModel::project(const Eigen::Vector3d& p) const {
  std::vector<cv::Point3d> obj{cv::Point3d(p.x(), p.y(), p.z())};
  std::vector<cv::Point2d> img;
  cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv::Mat(K), D.empty() ? cv::Mat() : cv::Mat(D), img);
  return img[0];
}

CameraModel CameraModel::cropped(const cv::Rect& region) const {
  CameraModel c = *this;
  c.width = region.width;
  c.height = region.height;
  c.K(0, 2) -= region.x;
  c.K(1, 2) -= region.y;
  return c;
}

cv::Rect CameraModel::regionAround(const Eigen::Vector3d& p, double size, int margin_px) const {
  const cv::Rect image(0, 0, width, height);
  if (margin_px <= 0 || !(p.z() > 0.05)) return image;
  const cv::Point2d c = project(p);
  const int half = static_cast<int>(margin_px + K(0, 0) * size / p.z());
  const cv::Rect region =
      cv::Rect(static_cast<int>(c.x) - half, static_cast<int>(c.y) - half, 2 * half, 2 * half) & image;
  return region.width < 16 || region.height < 16 ? image : region;
}

namespace {

// Undistorted normalised coordinates of the pixel centres (u, v) for u = -1..width,
// v = -1..height (one pixel of padding), CV_64FC2, row v + 1, column u + 1.
cv::Mat centreGrid(const CameraModel& cam) {
  const int w = cam.width + 2, h = cam.height + 2;
  cv::Mat pts(h * w, 1, CV_64FC2);
  auto* p = pts.ptr<cv::Vec2d>();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) *p++ = cv::Vec2d(x - 1.0, y - 1.0);
  }
  cv::Mat out;
  if (cam.D.empty()) {
    out.create(h * w, 1, CV_64FC2);
    const double fx = cam.K(0, 0), fy = cam.K(1, 1), cx = cam.K(0, 2), cy = cam.K(1, 2), s = cam.K(0, 1);
    const auto* in = pts.ptr<cv::Vec2d>();
    auto* o = out.ptr<cv::Vec2d>();
    for (int i = 0; i < h * w; ++i) {
      const double yn = (in[i][1] - cy) / fy;
      o[i] = cv::Vec2d((in[i][0] - cx - s * yn) / fx, yn);
    }
  } else {
    // Iterative inverse of the distortion, run to convergence (the default 5 iterations leave
    // ~0.01 px errors at the corners, which would bias an accuracy study).
    cv::undistortPoints(pts, out, cv::Mat(cam.K), cv::Mat(cam.D), cv::noArray(), cv::noArray(),
                        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-12));
  }
  return out.reshape(2, h);
}

// Rays for `n` x `n` samples per pixel (n = 1: pixel centres), CV_32FC2. The undistortion is
// solved exactly at pixel centres and interpolated bilinearly in between: the distortion map is
// so smooth that this is exact to ~1e-6 px, and it is n^2 times cheaper.
cv::Mat rayGrid(const cv::Mat& centres, const CameraModel& cam, int n) {
  const int w = cam.width * n, h = cam.height * n;
  cv::Mat out(h, w, CV_32FC2);
  cv::parallel_for_(cv::Range(0, h), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const double py = (y + 0.5) / n - 0.5 + 1.0;  // +1: padding row
      const int y0 = std::min(static_cast<int>(std::floor(py)), centres.rows - 2);
      const double fy = py - y0;
      const cv::Vec2d* r0 = centres.ptr<cv::Vec2d>(y0);
      const cv::Vec2d* r1 = centres.ptr<cv::Vec2d>(y0 + 1);
      cv::Vec2f* o = out.ptr<cv::Vec2f>(y);
      for (int x = 0; x < w; ++x) {
        const double px = (x + 0.5) / n - 0.5 + 1.0;
        const int x0 = std::min(static_cast<int>(std::floor(px)), centres.cols - 2);
        const double fx = px - x0;
        const cv::Vec2d v = (r0[x0] * (1 - fx) + r0[x0 + 1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x0 + 1] * fx) * fy;
        o[x] = cv::Vec2f(static_cast<float>(v[0]), static_cast<float>(v[1]));
      }
    }
  });
  return out;
}

// A plane prepared for ray casting in the camera frame.
struct PreparedPlane {
  Eigen::Vector3d n, t, ex, ey;  // normal, centre, unit axes (camera frame)
  double d;                      // n . t
  double half_w, half_h, tex_sx, tex_sy;
  double shade;                  // albedo * Lambert term (front side)
  double shade_back;             // the same from behind (two-sided planes)
  bool front_visible, back_visible;
  cv::Mat texture;               // CV_32FC1 or CV_32FC3 in 0..1
};

std::vector<PreparedPlane> prepare(const Scene& scene, bool color) {
  std::vector<PreparedPlane> out;
  Eigen::Vector3d light = scene.light.direction;
  if (light.norm() > 0) light.normalize();
  for (size_t i = 0; i < scene.planes.size(); ++i) {
    const Plane& pl = scene.planes[i];
    if (pl.texture.empty() || pl.texture.depth() != CV_8U ||
        (pl.texture.channels() != 1 && pl.texture.channels() != 3)) {
      throw std::invalid_argument("plane " + std::to_string(i) + ": texture must be a non-empty 8-bit 1- or 3-channel image");
    }
    if (!(pl.width > 0) || !(pl.height > 0)) {
      throw std::invalid_argument("plane " + std::to_string(i) + ": width and height must be > 0 metres");
    }
    PreparedPlane p;
    const Eigen::Matrix3d R = pl.pose.linear();
    p.ex = R.col(0);
    p.ey = R.col(1);
    p.n = R.col(2);
    p.t = pl.pose.translation();
    p.d = p.n.dot(p.t);
    p.half_w = pl.width / 2;
    p.half_h = pl.height / 2;
    p.tex_sx = pl.texture.cols / pl.width;
    p.tex_sy = pl.texture.rows / pl.height;
    const double lambert_front = std::max(0.0, p.n.dot(-light));
    const double lambert_back = std::max(0.0, (-p.n).dot(-light));
    p.shade = pl.albedo * (scene.light.ambient + scene.light.diffuse * lambert_front);
    p.shade_back = pl.albedo * (scene.light.ambient + scene.light.diffuse * lambert_back);
    // The camera (origin) sees the front face when it is on the +n side: n . (0 - t) > 0.
    p.front_visible = p.d < 0;
    p.back_visible = pl.two_sided && p.d > 0;
    if (!p.front_visible && !p.back_visible) continue;
    cv::Mat tex = pl.texture;
    if (color && tex.channels() == 1) cv::cvtColor(tex, tex, cv::COLOR_GRAY2BGR);
    if (!color && tex.channels() == 3) cv::cvtColor(tex, tex, cv::COLOR_BGR2GRAY);
    tex.convertTo(p.texture, color ? CV_32FC3 : CV_32FC1, 1.0 / 255.0);
    out.push_back(std::move(p));
  }
  return out;
}

// Bilinear texture lookup at texel coordinates (x, y) (texel centres at integers), clamped.
template <int C>
inline cv::Vec<float, C> sample(const cv::Mat& tex, double x, double y) {
  const int w = tex.cols, h = tex.rows;
  x = std::min(std::max(x, 0.0), w - 1.0);
  y = std::min(std::max(y, 0.0), h - 1.0);
  const int x0 = std::min(static_cast<int>(x), w - 2 < 0 ? 0 : w - 2);
  const int y0 = std::min(static_cast<int>(y), h - 2 < 0 ? 0 : h - 2);
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  using V = cv::Vec<float, C>;
  const V& a = tex.at<V>(y0, x0);
  const V& b = tex.at<V>(y0, x1);
  const V& c = tex.at<V>(y1, x0);
  const V& d = tex.at<V>(y1, x1);
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}

// Casts one ray (x, y, 1); returns the index of the nearest plane hit (or -1), its depth and colour.
template <int C>
inline int castRay(const std::vector<PreparedPlane>& planes, double rx, double ry, cv::Vec<float, C>* colour,
                   double* depth) {
  int best = -1;
  double best_z = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < planes.size(); ++k) {
    const PreparedPlane& p = planes[k];
    const double nr = p.n.x() * rx + p.n.y() * ry + p.n.z();
    if (std::abs(nr) < 1e-12) continue;
    const double z = p.d / nr;  // ray parameter = depth, since the ray's z is 1
    if (!(z > 0) || z >= best_z) continue;
    const Eigen::Vector3d q(rx * z - p.t.x(), ry * z - p.t.y(), z - p.t.z());
    const double lx = p.ex.dot(q), ly = p.ey.dot(q);
    if (std::abs(lx) > p.half_w || std::abs(ly) > p.half_h) continue;
    const cv::Vec<float, C> texel =
        sample<C>(p.texture, (lx + p.half_w) * p.tex_sx - 0.5, (p.half_h - ly) * p.tex_sy - 0.5);
    *colour = texel * static_cast<float>(p.front_visible ? p.shade : p.shade_back);
    best_z = z;
    best = static_cast<int>(k);
  }
  *depth = best_z;
  return best;
}

template <int C>
cv::Mat renderRadiance(const std::vector<PreparedPlane>& planes, const cv::Mat& rays, int n, int width, int height,
                       const cv::Mat& background) {
  using V = cv::Vec<float, C>;
  cv::Mat out(height, width, CV_32FC(C));
  const float inv = 1.0f / static_cast<float>(n * n);
  cv::parallel_for_(cv::Range(0, height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      V* o = out.ptr<V>(y);
      const V* bg = background.ptr<V>(y);
      for (int x = 0; x < width; ++x) {
        V acc = V::all(0);
        for (int j = 0; j < n; ++j) {
          const cv::Vec2f* r = rays.ptr<cv::Vec2f>(y * n + j) + x * n;
          for (int i = 0; i < n; ++i) {
            V c;
            double z;
            if (castRay<C>(planes, r[i][0], r[i][1], &c, &z) >= 0) acc += c;
            else acc += bg[x];
          }
        }
        o[x] = acc * inv;
      }
    }
  });
  return out;
}

}  // namespace

Renderer::Renderer(const CameraModel& camera, int supersampling) : camera_(camera), supersampling_(supersampling) {
  if (camera.width <= 0 || camera.height <= 0) throw std::invalid_argument("renderer: camera size must be > 0");
  if (supersampling < 1 || supersampling > 8) {
    throw std::invalid_argument("renderer: supersampling must be 1..8, got " + std::to_string(supersampling));
  }
  const cv::Mat centres = centreGrid(camera_);
  rays_ = rayGrid(centres, camera_, supersampling_);
  centre_rays_ = supersampling_ == 1 ? rays_ : rayGrid(centres, camera_, 1);
}

cv::Mat Renderer::render(const Scene& scene, const RenderOptions& options) const {
  const bool color = options.color;
  const int C = color ? 3 : 1;
  const std::vector<PreparedPlane> planes = prepare(scene, color);

  // Background radiance before the illumination scale (the wall is lit by the same scene light).
  cv::Mat background;
  if (!options.background_image.empty()) {
    cv::Mat bg = options.background_image;
    if (bg.depth() != CV_8U) throw std::invalid_argument("renderer: background_image must be 8-bit");
    if (color && bg.channels() == 1) cv::cvtColor(bg, bg, cv::COLOR_GRAY2BGR);
    if (!color && bg.channels() == 3) cv::cvtColor(bg, bg, cv::COLOR_BGR2GRAY);
    cv::resize(bg, bg, cv::Size(camera_.width, camera_.height), 0, 0, cv::INTER_AREA);
    bg.convertTo(background, CV_32FC(C), 1.0 / 255.0);
  } else {
    background = cv::Mat(camera_.height, camera_.width, CV_32FC(C), cv::Scalar::all(options.background));
  }

  cv::Mat radiance = color ? renderRadiance<3>(planes, rays_, supersampling_, camera_.width, camera_.height, background)
                           : renderRadiance<1>(planes, rays_, supersampling_, camera_.width, camera_.height, background);
  if (options.blur_sigma > 0) cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), options.blur_sigma);
  radiance *= 255.0 * options.illumination;
  if (options.noise_sigma > 0) {
    cv::Mat noise(radiance.size(), radiance.type());
    cv::RNG rng(options.seed == 0 ? 0x1234567ULL : options.seed);
    rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(options.noise_sigma));
    radiance += noise;
  }
  cv::Mat image;
  radiance.convertTo(image, CV_8UC(C));  // rounds and saturates
  return image;
}

cv::Mat Renderer::renderDepth(const Scene& scene) const {
  const std::vector<PreparedPlane> planes = prepare(scene, false);
  cv::Mat depth(camera_.height, camera_.width, CV_32FC1);
  cv::parallel_for_(cv::Range(0, camera_.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec2f* r = centre_rays_.ptr<cv::Vec2f>(y);
      float* d = depth.ptr<float>(y);
      for (int x = 0; x < camera_.width; ++x) {
        cv::Vec<float, 1> c;
        double z;
        d[x] = castRay<1>(planes, r[x][0], r[x][1], &c, &z) >= 0 ? static_cast<float>(z) : 0.0f;
      }
    }
  });
  return depth;
}

Eigen::Isometry3d lookAtOriginPose(double distance, double pan, double tilt) {
  Eigen::Isometry3d headon = Eigen::Isometry3d::Identity();
  headon.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  headon.translation() = Eigen::Vector3d(0, 0, distance);
  const Eigen::Isometry3d plane_camera = Eigen::Isometry3d(Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ())) *
                                         Eigen::Isometry3d(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX())) * headon;
  return plane_camera.inverse();
}

}  // namespace render
}  // namespace imagenets
