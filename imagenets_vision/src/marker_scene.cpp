#include "imagenets/vision/marker_scene.h"

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
  return renderer.render(scene, options);
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
