#include "imagenets/vision/marker_scene.h"

#include <cmath>
#include <map>
#include <mutex>
#include <tuple>
#include <vector>

namespace imagenets {
namespace marker {

cv::Mat renderView(const render::Renderer& renderer, render::Plane plane, const ViewSettings& view,
                   Eigen::Isometry3d* truth) {
  const Eigen::Isometry3d pose = render::lookAtOriginPose(view.distance, view.pan, view.tilt);
  plane.pose = pose;
  render::Scene scene;
  scene.planes.push_back(plane);
  // The light is fixed in the world (marker) frame; the renderer wants it in the camera frame.
  scene.light.direction = pose.linear() * view.light_direction;
  scene.light.ambient = view.ambient;
  scene.light.diffuse = view.diffuse;
  render::RenderOptions options;
  options.illumination = view.illumination;
  options.background = view.background;
  options.blur_sigma = view.blur;
  options.noise_sigma = view.noise;
  options.seed = view.seed;
  if (truth) *truth = pose;
  cv::Mat image = renderer.render(scene, options);
  if (view.highlight > 0 && pose.translation().z() > 0.05) {
    const double side_px = renderer.camera().K(0, 0) * view.marker_size / pose.translation().z();
    addSpecularHighlight(image, renderer.camera().project(pose.translation()) + view.highlight_offset * side_px,
                         view.highlight_sigma * side_px, view.highlight);
  }
  return image;
}

void addSpecularHighlight(cv::Mat& image, const cv::Point2d& centre, double sigma, double amplitude) {
  const int r = static_cast<int>(3 * sigma) + 1;
  const cv::Rect roi = cv::Rect(static_cast<int>(centre.x) - r, static_cast<int>(centre.y) - r, 2 * r + 1, 2 * r + 1) &
                       cv::Rect(0, 0, image.cols, image.rows);
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    uchar* row = image.ptr<uchar>(y);
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const double d2 = (x - centre.x) * (x - centre.x) + (y - centre.y) * (y - centre.y);
      const double add = amplitude * std::exp(-d2 / (2 * sigma * sigma));
      for (int ch = 0; ch < image.channels(); ++ch) {
        uchar& v = row[x * image.channels() + ch];
        v = cv::saturate_cast<uchar>(v + add);
      }
    }
  }
}

std::shared_ptr<const render::Renderer> sharedRenderer(const render::CameraModel& camera, int supersampling) {
  using Key = std::tuple<int, int, std::vector<double>, std::vector<double>, int>;
  static std::mutex mutex;
  static std::map<Key, std::shared_ptr<const render::Renderer>> cache;
  const Key key{camera.width, camera.height, std::vector<double>(camera.K.val, camera.K.val + 9), camera.D,
                supersampling};
  std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[key];
  if (!entry) entry = std::make_shared<const render::Renderer>(camera, supersampling);
  return entry;
}

void applyPrintReflectance(render::Plane* plane, double paper, double ink) {
  const double black = 255.0 * ink / paper;
  plane->texture.convertTo(plane->texture, CV_8U, (255.0 - black) / 255.0, black);
  plane->albedo = paper;
}

}  // namespace marker
}  // namespace imagenets
