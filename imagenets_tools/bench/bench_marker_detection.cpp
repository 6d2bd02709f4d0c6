// Marker detection speed on 1024x768 images of the marker study's scene (FRIEND camera, 600 mm):
// one detection at a fixed threshold, the full 40..80 feedback sweep through the robust marker
// detection net (sequential, parallel, coarse-to-fine), and libapriltag on the same views.
// Prints figures; run from the repository root: devel/lib/imagenets/bench_marker_detection
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <boost/make_shared.hpp>
#include <camera_calibration_parsers/parse.h>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>

#include "imagenets/vision/apriltag_marker.h"
#include "imagenets/vision/marker.h"
#include "marker_study/marker_net.h"
#include "imagenets/vision/marker_scene.h"
#include "imagenets/package_file.h"

using namespace imagenets;
using Clock = std::chrono::steady_clock;

namespace {

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// The machine's 1-minute load average: figures from a shared machine need it beside them.
std::string loadAverage() {
  double load = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = 0;
    std::fclose(f);
  }
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f", load);
  return buf;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

int main() {
  auto info = boost::make_shared<sensor_msgs::CameraInfo>();
  std::string name;
  if (!camera_calibration_parsers::readCalibration(imagenets::packageFile("imagenets_vision", "config/cameras/stereo_left.yaml"), name, *info)) {
    std::fprintf(stderr, "run from the repository root (config/cameras/friend_stereo_left.yaml not found)\n");
    return 1;
  }
  const render::CameraModel camera = render::CameraModel::fromCameraInfo(*info);
  const marker::MarkerDescription m = marker::MarkerDescription::load(imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"));
  const auto renderer = marker::sharedRenderer(camera, 4);
  render::Plane square = marker::markerPlane(m, Eigen::Isometry3d::Identity());
  marker::applyPrintReflectance(&square);
  marker::AprilTagOptions april;
  april.id = 0;
  render::Plane tag = marker::aprilTagPlane(april, 0, m.margin, Eigen::Isometry3d::Identity());
  marker::applyPrintReflectance(&tag);

  std::vector<cv::Mat> squares, tags;
  std::vector<double> render_ms;
  for (int i = 0; i < 16; ++i) {
    marker::ViewSettings v;
    v.pan = (i * 45 % 360) * M_PI / 180;
    v.tilt = (i % 8) * 10 * M_PI / 180;
    v.seed = i + 1;
    const auto t0 = Clock::now();
    squares.push_back(marker::renderView(*renderer, square, v, nullptr));
    render_ms.push_back(msSince(t0));
    tags.push_back(marker::renderView(*renderer, tag, v, nullptr));
  }
  const int reps = 3;
  std::printf("marker detection, 1024x768, %zu views x %d repetitions (medians, ms per image; load average %s)\n",
              squares.size(), reps, loadAverage().c_str());
  std::printf("  render (supersampling 4x4)                  %8.2f\n", median(render_ms));

  std::vector<double> direct;
  for (int r = 0; r < reps; ++r) {
    for (const auto& g : squares) {
      const auto t0 = Clock::now();
      cv::Mat bin;
      cv::threshold(g, bin, 60, 255, cv::THRESH_BINARY);
      const auto d = marker::detect(g, bin, camera, m);
      direct.push_back(msSince(t0));
      if (!d.found) std::fprintf(stderr, "warning: marker not found\n");
    }
  }
  std::printf("  square marker, threshold + detect (C++)     %8.2f\n", median(direct));

  struct Mode {
    const char* label;
    marker::ThresholdMode::Kind kind;
    const char* search;
    bool parallel;
    int threads;
  };
  using Kind = marker::ThresholdMode::Kind;
  const Mode modes[] = {{"net, fixed threshold 40", Kind::Fixed, "exhaustive", false, 1},
                        {"net, feedback 40..80 sequential (41 trials)", Kind::Range, "exhaustive", false, 1},
                        {"net, feedback 40..80 parallel, 2 threads", Kind::Range, "exhaustive", true, 2},
                        {"net, feedback 40..80 coarse-to-fine", Kind::Range, "coarse_to_fine", false, 1},
                        {"net as written (imagenets detect default)", Kind::AsWritten, "", false, 1}};
  double sequential = 0;
  for (const Mode& mode : modes) {
    marker::ThresholdMode tm;
    tm.kind = mode.kind;
    if (mode.kind == Kind::Range) tm.search = mode.search;
    tm.parallel = mode.parallel;
    marker::MarkerDetectionNet net(imagenets::packageFile("imagenets_blocks", "config/nets/robust_marker_detection.yaml"), imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"), tm,
                                   mode.threads);
    std::vector<double> t;
    double trials = 0;  // mean per image
    for (int r = 0; r < reps; ++r) {
      for (const auto& g : squares) {
        const auto msg = cv_bridge::CvImage(std_msgs::Header(), "mono8", g).toImageMsg();
        const auto res = net.run(msg, info);
        t.push_back(res.ms);
        if (res.trace) trials += static_cast<double>(res.trace->trials) / (reps * squares.size());
      }
    }
    const double med = median(t);
    if (std::string(mode.search) == "exhaustive" && mode.kind == Kind::Range && !mode.parallel) sequential = med;
    if (tm.feedback()) {
      std::printf("  %-44s%8.2f   (%.1f trials%s)\n", mode.label, med, trials,
                  sequential > 0 && med != sequential ? (", x" + std::to_string(sequential / med).substr(0, 4) +
                                                         " vs sequential").c_str()
                                                      : "");
    } else {
      std::printf("  %-44s%8.2f\n", mode.label, med);
    }
  }
  for (double decimate : {1.0, 2.0}) {
    marker::AprilTagOptions o = april;
    o.quad_decimate = decimate;
    const marker::AprilTagDetector detector(o);
    std::vector<double> t;
    for (int r = 0; r < reps; ++r) {
      for (const auto& g : tags) {
        const auto t0 = Clock::now();
        detector.detect(g, camera);
        t.push_back(msSince(t0));
      }
    }
    const std::string label = "libapriltag tag36h11, quad_decimate " + std::to_string(static_cast<int>(decimate));
    std::printf("  %-44s%8.2f\n", label.c_str(), median(t));
  }
  return 0;
}
