// The scene of the paper's marker study (Fig. 5.1): one marker plane at the origin of the world,
// a virtual camera on a sphere around it (distance, pan, tilt; see render::lookAtOriginPose), a
// directional light fixed in the world, an illumination level, blur and sensor noise. Shared by
// the MarkerRenderer block, `imagenets render-marker`, `imagenets marker-study` and the tests.
#pragma once

#include <cstdint>
#include <memory>

#include "imagenets/vision/render.h"

namespace imagenets {
namespace marker {

struct ViewSettings {
  double distance = 0.6;      // camera to marker centre, metres
  double pan = 0.0;           // radians, about the marker normal
  double tilt = 0.0;          // radians, away from the marker normal (0 = head-on)
  double illumination = 1.0;  // scene brightness (1 = nominal: white paper ~200 gray levels)
  Eigen::Vector3d light_direction{0.3, 0.4, -1.0};  // direction the light travels, marker frame
  double ambient = 0.4;
  double diffuse = 0.6;
  double background = 0.5;    // level of the wall behind (before illumination)
  double blur = 0.7;          // optical blur sigma, pixels
  double noise = 2.0;         // sensor noise sigma, gray levels
  std::uint64_t seed = 1;
  // A specular highlight near the marker (a lamp on the gripper's metal), after the noise:
  // `highlight` gray levels at its centre (0: none), centred `highlight_offset` from the marker's
  // centre, `highlight_sigma` wide; both in marker sides (`marker_size`, metres) in the image.
  double highlight = 0;
  cv::Point2d highlight_offset{0, 0};
  double highlight_sigma = 0.2;
  double marker_size = 0.06;
};

// Renders `plane` (its pose is replaced) as seen with `view`; returns the mono8 image and writes
// the true marker pose in the camera frame (T_camera_marker) to `truth`.
cv::Mat renderView(const render::Renderer& renderer, render::Plane plane, const ViewSettings& view,
                   Eigen::Isometry3d* truth);

// A specular highlight: a Gaussian spot of `sigma` pixels, `amplitude` gray levels at `centre`,
// added to every channel, saturating (the simulator's reflection fault, the study's reflections).
void addSpecularHighlight(cv::Mat& image, const cv::Point2d& centre, double sigma, double amplitude);

// One renderer per camera model and supersampling, shared (its ray grid costs ~0.3 s to build).
std::shared_ptr<const render::Renderer> sharedRenderer(const render::CameraModel& camera, int supersampling);

// Printed-paper reflectances used for marker textures: the texture's black becomes `ink`, its
// white `paper` (plane albedo). Real toner is not perfectly black, which is what makes a fixed
// threshold fail in bright scenes.
void applyPrintReflectance(render::Plane* plane, double paper = 0.85, double ink = 0.10);

}  // namespace marker
}  // namespace imagenets
