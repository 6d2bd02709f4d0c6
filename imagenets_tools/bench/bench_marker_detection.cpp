// Marker detection speed on 1024x768 images of the marker study's scene (FRIEND camera, 600 mm):
// the robust marker detection net at a fixed threshold next to a direct C++ call doing the same
// steps, the bare detector with its cheap defaults (a different, smaller job, labelled so), the
// feedback sweeps through the net (sequential, parallel, coarse-to-fine) and libapriltag as a peer.
// Prints figures and SUMMARY rows; run from the repository root: devel/lib/imagenets/bench_marker_detection
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <boost/make_shared.hpp>
#include <camera_calibration_parsers/parse.h>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>

#include "imagenets/bench_summary.h"
#include "imagenets/net.h"
#include "imagenets/package_file.h"
#include "imagenets/registry.h"
#include "imagenets/vision/apriltag_marker.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/vision/marker_scene.h"
#include "marker_study/marker_net.h"

using namespace imagenets;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kReps = 3;
constexpr int kFixedThreshold = 40;  // the net's fixed-threshold mode (marker_study's "fixed40")

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

std::string netPath() { return packageFile("imagenets_blocks", "config/nets/robust_marker_detection.yaml"); }
std::string markerPath() { return packageFile("imagenets_vision", "config/markers/gripper.yaml"); }

// The rendered views: the square marker and, in the same poses, an AprilTag of the same size.
struct Views {
  sensor_msgs::CameraInfoPtr info = boost::make_shared<sensor_msgs::CameraInfo>();
  render::CameraModel camera;
  marker::MarkerDescription marker;
  std::vector<cv::Mat> squares, tags;
  std::vector<double> render_ms;
};

Views renderViews() {
  Views v;
  std::string name;
  const std::string camera_file = packageFile("imagenets_vision", "config/cameras/stereo_left.yaml");
  if (!camera_calibration_parsers::readCalibration(camera_file, name, *v.info)) {
    throw std::runtime_error(camera_file + ": cannot read the camera calibration");
  }
  v.camera = render::CameraModel::fromCameraInfo(*v.info);
  v.marker = marker::MarkerDescription::load(markerPath());
  const auto renderer = marker::sharedRenderer(v.camera, 4);
  render::Plane square = marker::markerPlane(v.marker, Eigen::Isometry3d::Identity());
  marker::applyPrintReflectance(&square);
  marker::AprilTagOptions april;
  april.id = 0;
  render::Plane tag = marker::aprilTagPlane(april, 0, v.marker.margin, Eigen::Isometry3d::Identity());
  marker::applyPrintReflectance(&tag);
  for (int i = 0; i < 16; ++i) {
    marker::ViewSettings s;
    s.pan = (i * 45 % 360) * M_PI / 180;
    s.tilt = (i % 8) * 10 * M_PI / 180;
    s.seed = i + 1;
    const auto t0 = Clock::now();
    v.squares.push_back(marker::renderView(*renderer, square, s, nullptr));
    v.render_ms.push_back(msSince(t0));
    v.tags.push_back(marker::renderView(*renderer, tag, s, nullptr));
  }
  return v;
}

// Median ms per image of `detect_one` over every view, kReps times.
template <class F>
double timePerImage(const std::vector<cv::Mat>& images, F detect_one) {
  std::vector<double> t;
  for (int r = 0; r < kReps; ++r) {
    for (const auto& g : images) {
      const auto t0 = Clock::now();
      detect_one(g);
      t.push_back(msSince(t0));
    }
  }
  return median(t);
}

void printLine(const std::string& label, double ms, const std::string& note = "") {
  std::printf("  %-96s%8.2f%s\n", label.c_str(), ms, note.c_str());
}

// The options the net's `detector` block runs with, read from the net file through the block's
// own property parsing, so the direct call cannot drift from the net.
marker::DetectorOptions netDetectorOptions() {
  const NetSpec spec = parseNetFile(netPath());
  const auto block = BlockRegistry::instance().create("imagenets/SquareMarkerDetector");
  auto value = [&](const std::string& name) -> PropertyValue {
    const PropertySpec* property = block->findProperty(name);
    for (const BlockSpec& b : spec.blocks) {
      if (b.name != "detector") continue;
      for (const auto& p : b.properties) {
        if (p.name == name) return property->parse(p.text, spec.base_dir);
      }
    }
    return property->defaultValue();
  };
  marker::DetectorOptions o;
  o.min_confidence = std::get<double>(value("min_confidence"));
  o.refine_passes = std::get<int>(value("refine_passes"));
  o.min_inner_side_px = std::get<double>(value("min_inner_side_px"));
  o.edge_model = std::get<bool>(value("edge_model"));
  o.edge_model_max_side_px = std::get<double>(value("edge_model_max_side_px"));
  o.match_blur_px = std::get<std::vector<double>>(value("match_blur_px"));
  return o;
}

// The net's own steps at a fixed threshold, called directly: Otsu's threshold (the net's `otsu`
// block runs even when no feedback reads it), the fixed threshold, the detector with the net's
// options, and the detection message.
double benchDirectAsNet(const Views& v, const marker::DetectorOptions& options) {
  return timePerImage(v.squares, [&](const cv::Mat& g) {
    cv::Mat otsu, bin;
    cv::threshold(g, otsu, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    cv::threshold(g, bin, kFixedThreshold, 255, cv::THRESH_BINARY);
    const auto d = marker::detect(g, bin, v.camera, v.marker, options);
    marker::toMsg(d, v.marker, std_msgs::Header());
  });
}

// The bare detector with its defaults (2 refinement passes, no edge model, no blurred match) at
// threshold 60: much less work than the net does; a floor, not a baseline for the net.
double benchBareDetector(const Views& v) {
  return timePerImage(v.squares, [&](const cv::Mat& g) {
    cv::Mat bin;
    cv::threshold(g, bin, 60, 255, cv::THRESH_BINARY);
    if (!marker::detect(g, bin, v.camera, v.marker).found) std::fprintf(stderr, "warning: marker not found\n");
  });
}

struct Mode {
  const char* label;
  marker::ThresholdMode::Kind kind;
  const char* search;
  bool parallel;
  int threads;
};

// Median ms per image of the robust marker detection net in `mode`; `trials`: mean feedback trials.
double benchNet(const Views& v, const Mode& mode, double* trials) {
  marker::ThresholdMode tm;
  tm.kind = mode.kind;
  tm.fixed = kFixedThreshold;
  if (mode.kind == marker::ThresholdMode::Kind::Range) tm.search = mode.search;
  tm.parallel = mode.parallel;
  marker::MarkerDetectionNet net(netPath(), markerPath(), tm, mode.threads);
  std::vector<double> t;
  *trials = 0;
  for (int r = 0; r < kReps; ++r) {
    for (const auto& g : v.squares) {
      const auto msg = cv_bridge::CvImage(std_msgs::Header(), "mono8", g).toImageMsg();
      const auto res = net.run(msg, v.info);
      t.push_back(res.ms);
      if (res.trace) *trials += static_cast<double>(res.trace->trials) / (kReps * v.squares.size());
    }
  }
  return median(t);
}

double benchAprilTag(const Views& v, double decimate) {
  marker::AprilTagOptions o;
  o.id = 0;
  o.quad_decimate = decimate;
  const marker::AprilTagDetector detector(o);
  return timePerImage(v.tags, [&](const cv::Mat& g) { detector.detect(g, v.camera); });
}

// The net's feedback modes; returns the net as written (the one `imagenets detect` runs).
double printNetModes(const Views& v) {
  using Kind = marker::ThresholdMode::Kind;
  const Mode modes[] = {
      {"net, feedback 40..80 sequential: 41 x (threshold + detect as above)", Kind::Range, "exhaustive", false, 1},
      {"net, feedback 40..80 parallel, 2 threads", Kind::Range, "exhaustive", true, 2},
      {"net, feedback 40..80 coarse-to-fine", Kind::Range, "coarse_to_fine", false, 1},
      {"net as written (imagenets detect: from Otsu, coarse-to-fine, stop at 0.9)", Kind::AsWritten, "", false, 1}};
  double sequential = 0, as_written = 0;
  for (const Mode& mode : modes) {
    double trials = 0;
    const double ms = benchNet(v, mode, &trials);
    if (mode.kind == Kind::Range && !mode.parallel && std::string(mode.search) == "exhaustive") sequential = ms;
    if (mode.kind == Kind::AsWritten) as_written = ms;
    char note[64];
    std::snprintf(note, sizeof(note), "   (%.1f trials%s)", trials,
                  sequential > 0 && ms != sequential ? (", x" + std::to_string(sequential / ms).substr(0, 4) + " vs sequential").c_str() : "");
    printLine(mode.label, ms, note);
  }
  return as_written;
}

}  // namespace

int main() {
  const Views v = renderViews();
  std::printf("marker detection, 1024x768, %zu views x %d repetitions (medians, ms per image; load average %s)\n",
              v.squares.size(), kReps, loadAverage().c_str());
  printLine("render (supersampling 4x4)", median(v.render_ms));

  const marker::DetectorOptions options = netDetectorOptions();
  const std::string steps = "Otsu + threshold " + std::to_string(kFixedThreshold) + " + detect (" +
                            std::to_string(options.refine_passes) + " passes" +
                            (options.edge_model ? ", edge model" : "") +
                            (options.match_blur_px.empty() ? "" : ", blurred match") + ") + message";
  const double direct = benchDirectAsNet(v, options);
  printLine("direct C++: " + steps, direct);
  double unused = 0;
  const double net = benchNet(v, {"", marker::ThresholdMode::Kind::Fixed, "", false, 1}, &unused);
  printLine("net, fixed threshold 40: the same steps as blocks run by the executor", net,
            "   (x" + std::to_string(net / direct).substr(0, 4) + " the direct calls)");
  printLine("bare detector only: threshold 60 + detect defaults (2 passes, no edge model, no blurred match)",
            benchBareDetector(v), "   (less work: a floor, not the net's baseline)");
  const double as_written = printNetModes(v);
  double april[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    april[i] = benchAprilTag(v, i + 1.0);
    printLine("peer: libapriltag tag36h11, same poses, quad_decimate " + std::to_string(i + 1), april[i]);
  }
  printSummaryRow("marker detection, ms/image: net at threshold 40 vs direct calls, same steps", net, direct, "", false);
  printSummaryRow("marker detection, ms/image: net as written vs libapriltag (decimate 1)", as_written, april[0], "", false);
  return 0;
}
