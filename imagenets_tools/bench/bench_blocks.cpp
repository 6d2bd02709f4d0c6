// bench_blocks: time per 1024x768 image of the preprocessing and segmentation blocks and of SGBM
// stereo, each beside the raw OpenCV call it wraps. The ratio is what the block wrapper costs
// (input checks, message wrapping: cv_bridge copies the result into the message once).
// Prints figures and SUMMARY rows; passes or fails nothing.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/bench_summary.h"
#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

namespace {

double medianMs(const std::function<void()>& f, int runs) {
  f();  // warm-up (caches, lazy allocations)
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

void row(const char* name, BlockHarness& block, const std::function<void()>& raw, int runs) {
  const double b = medianMs([&] { block.run(); }, runs);
  const double r = medianMs(raw, runs);
  std::printf("%-26s %10.3f %10.3f %8.2f\n", name, b, r, b / r);
  imagenets::printSummaryRow(std::string("block vs the OpenCV call it wraps, ms/image: ") + name, b, r, "", false);
}

// A synthetic 1024x768 stereo pair, colour and gray, as messages and as images.
struct Inputs {
  sensor_msgs::ImageConstPtr left_msg, right_msg, gray_msg, right_gray_msg;
  cv::Mat left, right, gray, right_gray;
};

Inputs makeInputs() {
  Inputs in;
  BlockHarness pair("imagenets/SyntheticStereoPair");
  pair.set("width", 1024).set("height", 768).set("focal_length", 900.0).set("baseline", 0.12);
  pair.run();
  in.left_msg = pair.output<sensor_msgs::Image>("left");
  in.right_msg = pair.output<sensor_msgs::Image>("right");
  in.left = cv::Mat(768, 1024, CV_8UC3, const_cast<uint8_t*>(in.left_msg->data.data()), in.left_msg->step);
  in.right = cv::Mat(768, 1024, CV_8UC3, const_cast<uint8_t*>(in.right_msg->data.data()), in.right_msg->step);
  cv::cvtColor(in.left, in.gray, cv::COLOR_BGR2GRAY);
  cv::cvtColor(in.right, in.right_gray, cv::COLOR_BGR2GRAY);
  in.gray_msg = toImageMsg(in.gray, "mono8", in.left_msg->header);
  in.right_gray_msg = toImageMsg(in.right_gray, "mono8", in.right_msg->header);
  return in;
}

void benchPreprocessing(const Inputs& in, int runs) {
  const auto& left_msg = in.left_msg;
  const auto& gray_msg = in.gray_msg;
  const cv::Mat &left = in.left, &gray = in.gray;
  cv::Mat out;
  BlockHarness grayscale("imagenets/Grayscale");
  grayscale.input("image", left_msg);
  row("Grayscale (bgr8)", grayscale, [&] { cv::cvtColor(left, out, cv::COLOR_BGR2GRAY); }, runs);

  BlockHarness blur("imagenets/GaussianBlur");
  blur.input("image", gray_msg);
  row("GaussianBlur 5x5", blur, [&] { cv::GaussianBlur(gray, out, cv::Size(5, 5), 0); }, runs);

  BlockHarness contrast("imagenets/ContrastNormalization");
  contrast.input("image", gray_msg);
  row("ContrastNormalization", contrast, [&] {
    double lo, hi;
    cv::minMaxLoc(gray, &lo, &hi);
    gray.convertTo(out, CV_8U, 255 / (hi - lo), -lo * 255 / (hi - lo));
  }, runs);

  BlockHarness equalize("imagenets/HistogramEqualization");
  equalize.input("image", gray_msg);
  row("HistogramEqualization", equalize, [&] { cv::equalizeHist(gray, out); }, runs);

  // Rectify with a distorted model: the block caches its remap tables, like the raw code would.
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->width = 1024;
  info->height = 768;
  info->distortion_model = "plumb_bob";
  info->D = {-0.2, 0.05, 0, 0, 0};
  info->K = {900, 0, 511.5, 0, 900, 383.5, 0, 0, 1};
  info->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info->P = {900, 0, 511.5, 0, 0, 900, 383.5, 0, 0, 0, 1, 0};
  cv::Mat map1, map2;
  cv::initUndistortRectifyMap(cv::Matx33d(info->K.data()), info->D, cv::Matx33d(info->R.data()),
                              cv::Matx33d(900, 0, 511.5, 0, 900, 383.5, 0, 0, 1), cv::Size(1024, 768), CV_16SC2, map1,
                              map2);
  BlockHarness rectify("imagenets/Rectify");
  rectify.input("image", gray_msg).input("camera_info", info);
  row("Rectify (mono8)", rectify, [&] { cv::remap(gray, out, map1, map2, cv::INTER_LINEAR); }, runs);

  BlockHarness crop("imagenets/CropRoi");
  crop.set("x", 100).set("y", 100).set("width", 640).set("height", 480).input("image", gray_msg);
  row("CropRoi 640x480", crop, [&] { out = gray(cv::Rect(100, 100, 640, 480)).clone(); }, runs);
}

void benchSegmentationAndStereo(const Inputs& in, int runs) {
  const auto& left_msg = in.left_msg;
  const auto& gray_msg = in.gray_msg;
  const cv::Mat &left = in.left, &gray = in.gray;
  cv::Mat out;

  BlockHarness threshold("imagenets/Threshold");
  threshold.input("image", gray_msg);
  row("Threshold", threshold, [&] { cv::threshold(gray, out, 128, 255, cv::THRESH_BINARY); }, runs);

  BlockHarness otsu("imagenets/OtsuThreshold");
  otsu.input("image", gray_msg);
  row("OtsuThreshold", otsu, [&] { cv::threshold(gray, out, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU); }, runs);

  BlockHarness adaptive("imagenets/AdaptiveThreshold");
  adaptive.input("image", gray_msg);
  row("AdaptiveThreshold 21", adaptive, [&] {
    cv::adaptiveThreshold(gray, out, 255, cv::ADAPTIVE_THRESH_MEAN_C, cv::THRESH_BINARY, 21, 5);
  }, runs);

  BlockHarness colour("imagenets/ColourRange");
  colour.input("image", left_msg);
  row("ColourRange (HSV)", colour, [&] {
    cv::Mat hsv;
    cv::cvtColor(left, hsv, cv::COLOR_BGR2HSV);
    cv::inRange(hsv, cv::Scalar(0, 100, 100), cv::Scalar(10, 255, 255), out);
  }, runs);

  BlockHarness sgbm_block("imagenets/StereoDisparity");
  sgbm_block.input("left", gray_msg).input("right", in.right_gray_msg);
  auto sgbm = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 1, 63, 10, 100, 2, cv::StereoSGBM::MODE_SGBM);
  row("StereoDisparity SGBM 128", sgbm_block, [&] { sgbm->compute(gray, in.right_gray, out); }, 5);
}

}  // namespace

int main() {
  const int runs = 25;
  const Inputs in = makeInputs();
  std::printf("1024x768, median of %d runs (SGBM: 5)\n", runs);
  std::printf("%-26s %10s %10s %8s\n", "block", "block ms", "OpenCV ms", "ratio");
  benchPreprocessing(in, runs);
  benchSegmentationAndStereo(in, runs);
  return 0;
}
