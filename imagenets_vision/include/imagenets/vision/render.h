// A small ray-casting renderer for textured planar patches seen by a real (distorted) pinhole
// camera: the paper's Fig. 5.1 "generate 3D projected marker images for known camera positions",
// and the simulated robot's stereo and hand cameras (gripper marker, table, boxes).
//
//   render::CameraModel cam = render::CameraModel::fromCameraInfo(info);
//   render::Renderer renderer(cam, /*supersampling=*/4);   // precomputes one ray per sub-pixel
//   render::Plane marker;
//   marker.texture = cv::imread("marker.png", cv::IMREAD_GRAYSCALE);
//   marker.width = marker.height = 0.060;                  // metres
//   marker.pose = T_camera_marker;                         // plane frame in the camera frame
//   render::Scene scene;  scene.planes.push_back(marker);
//   cv::Mat image = renderer.render(scene, render::RenderOptions());   // CV_8UC1 or CV_8UC3
//
// Conventions (REP-103, camera optical frame: x right, y down, z forward). A plane's own frame
// has its origin at the centre of the patch, x to the right of the texture, y towards the top row
// of the texture, z out of the visible face (so a patch facing the camera head-on has
// R = diag(1, -1, -1)). That is the ARToolKit / OpenCV-aruco marker frame, so the pose of a
// rendered marker is directly the ground truth a marker detector should report.
//
// Radiometry (all levels in [0, 1] of the sensor's full scale before noise):
//   value = illumination * albedo * texture * (ambient + diffuse * max(0, n . -light_direction))
// and the background is `illumination * background` (a flat, unshaded wall far behind).
// Then optical blur (Gaussian, sigma in output pixels), sensor noise (Gaussian, sigma in gray
// levels, seeded: the same seed gives the same image), rounding and clipping to 8 bits.
//
// Thread safety: render() is const and may be called concurrently on one Renderer.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace sensor_msgs {
template <class Allocator>
struct CameraInfo_;
typedef CameraInfo_<std::allocator<void>> CameraInfo;
}  // namespace sensor_msgs

namespace imagenets {
namespace render {

// Pinhole camera with OpenCV distortion (plumb_bob: k1 k2 p1 p2 k3, or rational_polynomial: 8).
struct CameraModel {
  int width = 0, height = 0;
  cv::Matx33d K = cv::Matx33d::eye();
  std::vector<double> D;  // empty = no distortion

  // From a ROS camera_info (uses K and D of the raw image, not P). Throws std::invalid_argument
  // for a zero size, a singular K or an unsupported distortion model.
  static CameraModel fromCameraInfo(const sensor_msgs::CameraInfo& info);
  // Projects a point in the camera frame to distorted pixel coordinates (z must be > 0).
  cv::Point2d project(const Eigen::Vector3d& p_camera) const;
  // The model of a region of this camera's image (size of the region, principal point moved).
  CameraModel cropped(const cv::Rect& region) const;
  // The square region around where an object of `size` metres centred at `p_camera` appears: its
  // projected size plus `margin_px` on each side, clipped to the image. The whole image when
  // margin_px <= 0, when the point is less than 5 cm in front of the camera, or when the clipped
  // region is narrower than 16 pixels.
  cv::Rect regionAround(const Eigen::Vector3d& p_camera, double size, int margin_px) const;
};

// One textured rectangle in the scene.
struct Plane {
  cv::Mat texture;          // CV_8UC1 or CV_8UC3 (BGR); row 0 is the top edge (+y of the plane)
  double width = 0.1;       // metres along the plane's x
  double height = 0.1;      // metres along the plane's y
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // plane frame in the camera frame
  double albedo = 1.0;      // reflectance scale applied to the texture (0..1)
  bool two_sided = false;   // false: invisible from behind (back-face culled)
};

// A directional light (like the sun, or a distant lamp), plus ambient light.
struct Light {
  Eigen::Vector3d direction{0.0, 0.0, 1.0};  // direction the light travels, camera frame
  double diffuse = 0.6;                      // share of directional (Lambertian) light
  double ambient = 0.4;                      // share of light that comes from everywhere
};

struct Scene {
  std::vector<Plane> planes;  // nearest plane wins where planes overlap (depth test per ray)
  Light light;
};

struct RenderOptions {
  double illumination = 1.0;      // scene brightness / exposure scale (1 = nominal)
  double background = 0.5;        // uniform background level (0..1) where no plane is hit
  cv::Mat background_image;       // optional: 8-bit image (resized to the camera) instead of `background`
  double blur_sigma = 0.5;        // optical blur in output pixels (0 = none)
  double noise_sigma = 1.0;       // Gaussian sensor noise in gray levels (0 = none)
  std::uint64_t seed = 0;         // noise seed
  bool color = false;             // true: CV_8UC3 BGR output; false: CV_8UC1 (textures converted)
};

class Renderer {
 public:
  // `supersampling` n: n x n rays per output pixel, averaged (anti-aliasing). 1..8.
  explicit Renderer(const CameraModel& camera, int supersampling = 4);

  const CameraModel& camera() const { return camera_; }
  int supersampling() const { return supersampling_; }

  cv::Mat render(const Scene& scene, const RenderOptions& options = RenderOptions()) const;
  // CV_32FC1 depth (z in the camera frame) at output resolution, sampled at pixel centres.
  cv::Mat renderDepth(const Scene& scene) const;

 private:
  CameraModel camera_;
  int supersampling_;
  cv::Mat rays_;         // CV_32FC2: undistorted normalised (x, y) per sub-pixel sample
  cv::Mat centre_rays_;  // CV_32FC2: the same at output pixel centres
};

// Pose helper for a camera looking at the origin (the paper's study, Fig. 5.1): the camera
// starts head-on at `distance` on the plane's +z axis (image x along the plane's x, image up
// along the plane's +y), is tilted by `tilt` about the plane's x axis and then panned by `pan`
// about the plane's z axis, always looking at the origin:
//   T_plane_camera = Rz(pan) * Rx(tilt) * T_headon,  T_headon = [diag(1,-1,-1) | (0,0,distance)].
// Returns the plane pose in the camera frame (T_camera_plane). Angles in radians.
Eigen::Isometry3d lookAtOriginPose(double distance, double pan, double tilt);

}  // namespace render
}  // namespace imagenets
