#include <cmath>

#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"
#include "imagenets/time.h"

namespace imagenets {
namespace blocks {

// A rectified stereo pair of a scene with known depth: a textured wall parallel to the image
// plane at `far_depth` and, in front of it, a textured square board at `near_depth` (a
// fronto-parallel plane has the constant disparity fx * baseline / depth). The texture is fixed
// on the surfaces (smooth colour noise), so both cameras see the same surface points. With the
// camera models and the true depth, this is the test and benchmark input for the stereo blocks.
class SyntheticStereoPair : public Block {
 public:
  SyntheticStereoPair() {
    addOutput<sensor_msgs::Image>("left", "left image, bgr8");
    addOutput<sensor_msgs::Image>("right", "right image, bgr8");
    addOutput<sensor_msgs::CameraInfo>("left_info", "left model (rectified: D = 0, R = I)");
    addOutput<sensor_msgs::CameraInfo>("right_info", "right model: P[3] = -fx * baseline");
    addOutput<sensor_msgs::Image>("depth", "true depth along the left optical axis (32FC1, metres)");
    addProperty<int>("width", 640, "image width (pixels)").range(64, 4096);
    addProperty<int>("height", 480, "image height (pixels)").range(48, 4096);
    addProperty<double>("focal_length", 600.0, "fx = fy (pixels)").range(10, 100000);
    addProperty<double>("baseline", 0.12, "distance between the camera centres (m)").range(0.001, 10);
    addProperty<double>("far_depth", 3.0, "depth of the wall (m)").range(0.1, 1000);
    addProperty<double>("near_depth", 1.5, "depth of the board (m); >= far_depth: no board").range(0.1, 1000);
    addProperty<double>("near_size", 0.8, "side length of the board (m), centred on the left optical axis")
        .range(0, 100);
    addProperty<double>("texture_scale", 0.006, "texture cell size on the wall (m); the board's is half").range(1e-5, 10);
    addProperty<int>("seed", 1, "random seed of the texture").range(0, 1000000);
    addProperty<std::string>("left_frame", "left_camera_optical", "frame_id of the left camera");
    addProperty<std::string>("right_frame", "right_camera_optical", "frame_id of the right camera");
  }

  void process(Context& ctx) override {
    const int w = ctx.property<int>("width"), h = ctx.property<int>("height");
    const double f = ctx.property<double>("focal_length"), b = ctx.property<double>("baseline");
    const double far = ctx.property<double>("far_depth"), near = ctx.property<double>("near_depth");
    const double half = 0.5 * ctx.property<double>("near_size"), cell = ctx.property<double>("texture_scale");
    const double cx = (w - 1) / 2.0, cy = (h - 1) / 2.0;
    cv::RNG rng(static_cast<uint64_t>(ctx.property<int>("seed")) + 1);
    const Texture wall(rng, cell, {1.0, 0.85, 0.6}), board(rng, cell / 2, {0.5, 0.8, 1.0});

    // Left camera at the origin, right camera at (b, 0, 0); both look along +z.
    cv::Mat depth(h, w, CV_32FC1);
    auto render = [&](double camera_x, cv::Mat& image, bool record_depth) {
      image.create(h, w, CV_8UC3);
      for (int v = 0; v < h; ++v) {
        for (int u = 0; u < w; ++u) {
          cv::Vec3d sum(0, 0, 0);
          double z_centre = far;
          for (int s = 0; s < 4; ++s) {  // 2x2 supersampling against aliasing
            const double du = (s % 2 ? 0.25 : -0.25), dv = (s / 2 ? 0.25 : -0.25);
            const double rx = (u + du - cx) / f, ry = (v + dv - cy) / f;
            const double nx = camera_x + rx * near, ny = ry * near;
            const bool on_board = near < far && std::abs(nx) <= half && std::abs(ny) <= half;
            sum += on_board ? board.at(nx, ny) : wall.at(camera_x + rx * far, ry * far);
            if (s == 0) z_centre = on_board ? near : far;
          }
          image.at<cv::Vec3b>(v, u) = cv::Vec3b(cv::saturate_cast<uchar>(sum[0] / 4), cv::saturate_cast<uchar>(sum[1] / 4),
                                                cv::saturate_cast<uchar>(sum[2] / 4));
          if (record_depth) depth.at<float>(v, u) = static_cast<float>(z_centre);
        }
      }
    };
    cv::Mat left, right;
    render(0.0, left, true);
    render(b, right, false);

    std_msgs::Header lh, rh;
    lh.stamp = rh.stamp = now();
    lh.frame_id = ctx.property<std::string>("left_frame");
    rh.frame_id = ctx.property<std::string>("right_frame");
    auto info = [&](const std_msgs::Header& header, double tx) {
      sensor_msgs::CameraInfo::Ptr i(new sensor_msgs::CameraInfo);
      i->header = header;
      i->width = w;
      i->height = h;
      i->distortion_model = "plumb_bob";
      i->D = {0, 0, 0, 0, 0};
      i->K = {f, 0, cx, 0, f, cy, 0, 0, 1};
      i->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      i->P = {f, 0, cx, tx, 0, f, cy, 0, 0, 0, 1, 0};
      return i;
    };
    ctx.output("left", toImageMsg(left, "bgr8", lh));
    ctx.output("right", toImageMsg(right, "bgr8", rh));
    ctx.output("left_info", info(lh, 0.0));
    ctx.output("right_info", info(rh, -f * b));
    ctx.output("depth", toImageMsg(depth, "32FC1", lh));
  }

 private:
  // Smooth colour value noise on a plane: random values on a square grid, bilinear in between,
  // two octaves; tinted per surface.
  struct Texture {
    static constexpr int kSize = 512;
    cv::Mat grid;  // kSize x kSize x 3 (channel 0 used), wraps around
    double cell;
    cv::Vec3d tint;
    Texture(cv::RNG& rng, double cell_size, cv::Vec3d t) : grid(kSize, kSize, CV_32FC3), cell(cell_size), tint(t) {
      rng.fill(grid, cv::RNG::UNIFORM, 0.0, 1.0);
    }
    cv::Vec3d sample(double gx, double gy) const {
      const double fx = std::floor(gx), fy = std::floor(gy);
      const double ax = gx - fx, ay = gy - fy;
      auto g = [&](long x, long y) {
        return cv::Vec3d(grid.at<cv::Vec3f>(static_cast<int>(((y % kSize) + kSize) % kSize),
                                            static_cast<int>(((x % kSize) + kSize) % kSize)));
      };
      const long x0 = static_cast<long>(fx), y0 = static_cast<long>(fy);
      return (1 - ay) * ((1 - ax) * g(x0, y0) + ax * g(x0 + 1, y0)) + ay * ((1 - ax) * g(x0, y0 + 1) + ax * g(x0 + 1, y0 + 1));
    }
    cv::Vec3d at(double x, double y) const {
      const cv::Vec3d n = 0.7 * sample(x / cell, y / cell) + 0.3 * sample(x / (4 * cell) + 100.5, y / (4 * cell) + 7.25);
      // Luminance texture (what block matching needs; it also keeps PNG files small), tinted.
      const double lum = n[0];
      cv::Vec3d c;
      for (int k = 0; k < 3; ++k) c[k] = 255.0 * tint[k] * (0.1 + 0.9 * lum);
      return c;
    }
  };
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SyntheticStereoPair, "imagenets/SyntheticStereoPair", "stereo",
                         "Renders a rectified stereo pair of textured planes at known depth");
