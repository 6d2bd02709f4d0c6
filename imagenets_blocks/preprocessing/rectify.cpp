#include <map>
#include <mutex>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Undistorts and rectifies an image with its camera_info (K, D, R, P), as image_proc does: the
// result is the ideal pinhole image of P, with a camera_info that has no distortion.
class Rectify : public Block {
 public:
  Rectify() {
    addInput<sensor_msgs::Image>("image", "raw image (mono8, bgr8, rgb8, mono16)");
    addInput<sensor_msgs::CameraInfo>("camera_info", "its calibration (same size; plumb_bob, rational_polynomial or equidistant)");
    addOutput<sensor_msgs::Image>("image", "rectified image, same encoding and size");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "model of the rectified image: K from P, D = 0, R = I");
    addProperty<std::string>("interpolation", "linear", "pixel interpolation").choices({"nearest", "linear", "cubic"});
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8", "mono16", "bgra8", "rgba8"}, &encoding, &header);
    auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
    if (!info) throw BlockError("input 'camera_info': missing");
    if (info->width != static_cast<unsigned>(in.cols) || info->height != static_cast<unsigned>(in.rows)) {
      throw BlockError("input 'camera_info' is for " + std::to_string(info->width) + "x" + std::to_string(info->height) +
                       " images, input 'image' is " + std::to_string(in.cols) + "x" + std::to_string(in.rows));
    }
    if (info->K[0] <= 0 || info->K[4] <= 0) throw BlockError("input 'camera_info': K has no focal length (not calibrated)");
    if (info->P[0] <= 0 || info->P[5] <= 0) throw BlockError("input 'camera_info': P has no focal length");
    const std::string& model = info->distortion_model;
    if (model != "plumb_bob" && model != "rational_polynomial" && model != "equidistant" && !model.empty()) {
      throw BlockError("input 'camera_info': distortion model '" + model + "' not supported");
    }
    if (model == "equidistant" && info->D.size() != 4) {
      throw BlockError("input 'camera_info': equidistant model needs 4 coefficients in D, has " +
                       std::to_string(info->D.size()));
    }

    std::shared_ptr<const Maps> maps = mapsFor(*info);
    static const std::map<std::string, int> kInterpolation{
        {"nearest", cv::INTER_NEAREST}, {"linear", cv::INTER_LINEAR}, {"cubic", cv::INTER_CUBIC}};
    OutputImage out = newOutputImage(cv::Size(in.cols, in.rows), in.type(), encoding, header);
    cv::remap(in, out.mat, maps->map1, maps->map2, kInterpolation.at(ctx.property<std::string>("interpolation")),
              cv::BORDER_CONSTANT);
    sensor_msgs::CameraInfo::Ptr rectified(new sensor_msgs::CameraInfo(*info));
    rectified->header = header;
    rectified->D.assign(info->D.size(), 0.0);
    rectified->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    rectified->K = {info->P[0], info->P[1], info->P[2], info->P[4], info->P[5], info->P[6], 0, 0, 1};
    ctx.output("image", out.msg);
    ctx.output("camera_info", rectified);
  }

 private:
  struct Maps {
    sensor_msgs::CameraInfo key;
    cv::Mat map1, map2;
  };

  // The remap tables depend only on the model: kept for the last model seen (a cache shared by
  // concurrent runs, not per-run state).
  std::shared_ptr<const Maps> mapsFor(const sensor_msgs::CameraInfo& info) {
    sensor_msgs::CameraInfo key = info;
    key.header = std_msgs::Header();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (cache_ && cache_->key.K == key.K && cache_->key.D == key.D && cache_->key.R == key.R &&
          cache_->key.P == key.P && cache_->key.width == key.width && cache_->key.height == key.height &&
          cache_->key.distortion_model == key.distortion_model) {
        return cache_;
      }
    }
    auto maps = std::make_shared<Maps>();
    maps->key = key;
    const cv::Matx33d K(info.K.data()), R(info.R.data());
    const cv::Matx34d P(info.P.data());
    const cv::Mat D(info.D, true);
    const cv::Size size(info.width, info.height);
    if (info.distortion_model == "equidistant") {
      cv::fisheye::initUndistortRectifyMap(K, D, R, P.get_minor<3, 3>(0, 0), size, CV_16SC2, maps->map1, maps->map2);
    } else {
      cv::initUndistortRectifyMap(K, D, R, P.get_minor<3, 3>(0, 0), size, CV_16SC2, maps->map1, maps->map2);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    cache_ = maps;
    return maps;
  }

  std::mutex mutex_;
  std::shared_ptr<const Maps> cache_;
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::Rectify, "imagenets/Rectify", "preprocessing",
                         "Undistorts and rectifies an image with its camera_info");
