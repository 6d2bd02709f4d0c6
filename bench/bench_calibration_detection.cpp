// bench_calibration_detection: what one calibration sample costs in image processing -- the
// robust marker detection (marker_measurement.h) of the left and right image -- and how accurate
// it is, on the simulator's own renderings of the joint method's ten poses (true geometry, default
// noise), then again with a spurious reflection near the marker in about half of the views
// (friend_calibration/test/calibration_views.h).
// Compared: the calibration's hand-written detection (Otsu threshold first, stop when good, else
// the coarse-to-fine sweep) next to the same method declared as a net
// (config/nets/calibration_marker_detection.yaml, the engine's generic feedback), then always
// sweeping, an exhaustive sweep, a single fixed threshold (no feedback) and the whole image
// instead of the predicted region. Times are CPU time of the detecting thread (robust to a loaded
// machine; the net runs on an executor with one thread, the caller's) and wall time of a
// left+right pair detected in parallel, as the node does.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "calibration_views.h"
#include "friend_calibration/calibration.h"
#include "friend_calibration/calibration_marker_net.h"
#include "friend_calibration/marker_measurement.h"
#include "imagenets/blocks/image.h"

using namespace friend_calibration;
using Clock = std::chrono::steady_clock;

namespace {

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

// Accuracy is counted apart for clean views and for views with a reflection whose detection
// passes the calibration's reprojection gate (FusionLimits::min_reprojection_error, the limit
// for this camera's noise): a disturbed detection the gate lets through is what biases a result.
struct Figures {
  double cpu_ms = 0, pair_wall_ms = 0, clean_worst_mm = 0, clean_sum_mm = 0, clean_sum_deg = 0, gated_worst_mm = 0;
  int clean = 0, clean_found = 0, disturbed = 0, disturbed_found = 0, disturbed_passed = 0;
};

// `detect(view, side)`: one detection; side 0 (left) and 1 (right) run in parallel.
using Detect = std::function<MarkerObservation(const CalibrationView&, int side)>;

Figures measure(const std::vector<CalibrationView>& views, const Detect& detect) {
  Figures f;
  auto one = [&](const CalibrationView& v, int side, double* cpu) {
    const double c0 = threadCpuMs();
    MarkerObservation o = detect(v, side);
    *cpu = threadCpuMs() - c0;
    return o;
  };
  for (size_t i = 0; i + 1 < views.size(); i += 2) {  // left, right of one pose
    double cpu_l = 0, cpu_r = 0;
    const auto t0 = Clock::now();
    auto right = std::async(std::launch::async, one, std::cref(views[i + 1]), 1, &cpu_r);
    const MarkerObservation left = one(views[i], 0, &cpu_l);
    const MarkerObservation r = right.get();
    f.pair_wall_ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    f.cpu_ms += cpu_l + cpu_r;
    for (const auto& [o, v] : {std::make_pair(left, &views[i]), std::make_pair(r, &views[i + 1])}) {
      if (std::getenv("VERBOSE")) {
        std::printf("  view %ld%s: found %d conf %.3f thr %.0f reproj %.3f err %.3f mm %s\n", static_cast<long>(v - views.data()),
                    v->reflection ? " (reflection)" : "", o.found, o.confidence, o.threshold, o.reprojection_error,
                    o.found ? (o.pose.translation() - v->truth.translation()).norm() * 1000 : 0.0, o.reason.c_str());
      }
      const double mm = (o.pose.translation() - v->truth.translation()).norm() * 1000;
      if (!v->reflection) {
        ++f.clean;
        if (!o.found) continue;
        ++f.clean_found;
        f.clean_sum_mm += mm;
        f.clean_sum_deg += angleBetween(o.pose, v->truth) * 180 / M_PI;
        f.clean_worst_mm = std::max(f.clean_worst_mm, mm);
      } else {
        ++f.disturbed;
        if (!o.found) continue;
        ++f.disturbed_found;
        if (o.reprojection_error > FusionLimits().min_reprojection_error) continue;
        ++f.disturbed_passed;
        f.gated_worst_mm = std::max(f.gated_worst_mm, mm);
      }
    }
  }
  return f;
}

}  // namespace

int main() {
  const CalibrationViews data = renderCalibrationViews();
  const std::vector<CalibrationView>& views = data.views;
  const auto& marker = data.marker;
  int reflections = 0;
  for (const auto& v : views) reflections += v.reflection;
  std::printf("robust marker detection for the calibration: %zu views of 1024x768 (10 joint-method poses x left/right,\n"
              "twice; %d with a spurious reflection), region of interest from the nominal prediction;\n"
              "errors against the true marker pose in the camera frame; 'passed': reflection-disturbed detections\n"
              "with a reprojection error within the calibration's gate (%.2f px)\n",
              views.size(), reflections, FusionLimits().min_reprojection_error);
  std::printf("%-48s %10s %12s | %-12s %7s %8s %8s | %-12s %-6s %8s\n", "sweep", "CPU ms/img", "pair wall ms",
              "clean found", "mean mm", "mean deg", "worst mm", "refl. found", "passed", "worst mm");
  struct Variant {
    std::string name;
    Detect detect;
  };
  auto handWritten = [&](const RobustDetectionOptions& options) -> Detect {
    return [&marker, options](const CalibrationView& v, int) {
      return detectMarkerRobustly(v.image, v.info, marker, v.predicted, options);
    };
  };
  // The net gets the image as the node receives it (a ROS message), converted before timing.
  std::vector<sensor_msgs::ImageConstPtr> messages;
  for (const auto& v : views) messages.push_back(imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header));
  CalibrationMarkerNet nets[2];  // one per camera: the two run in parallel
  const Detect as_net = [&](const CalibrationView& v, int side) {
    return nets[side].detect(messages[&v - views.data()], v.info, v.predicted);
  };
  std::vector<Variant> variants;
  variants.push_back({"calibration default (Otsu first, stop if good)", handWritten(RobustDetectionOptions())});
  variants.push_back({"the same as a net (calibration_marker_detection)", as_net});
  RobustDetectionOptions always_sweep;
  always_sweep.good_score = 0;
  variants.push_back({"always the coarse-to-fine sweep", handWritten(always_sweep)});
  RobustDetectionOptions exhaustive;
  exhaustive.coarse_from = 20;
  exhaustive.coarse_to = 235;
  exhaustive.coarse_step = 5;
  exhaustive.fine_step = 0;
  exhaustive.good_score = 0;
  variants.push_back({"exhaustive 20..235 step 5", handWritten(exhaustive)});
  RobustDetectionOptions fixed = always_sweep;
  fixed.coarse_from = fixed.coarse_to = 120;
  fixed.fine_step = 0;
  variants.push_back({"fixed threshold 120 (no feedback)", handWritten(fixed)});
  RobustDetectionOptions whole = always_sweep;
  whole.roi_margin_px = 0;
  variants.push_back({"always sweep, whole image (no ROI)", handWritten(whole)});
  auto print = [](const std::string& name, const Figures& f) {
    const int views = f.clean + f.disturbed;
    std::printf("%-48s %10.2f %12.2f | %4d / %-5d %7.3f %8.4f %8.3f | %4d / %-5d %-6d %8.3f\n", name.c_str(),
                f.cpu_ms / views, f.pair_wall_ms / (views / 2), f.clean_found, f.clean,
                f.clean_found ? f.clean_sum_mm / f.clean_found : 0, f.clean_found ? f.clean_sum_deg / f.clean_found : 0,
                f.clean_worst_mm, f.disturbed_found, f.disturbed, f.disturbed_passed, f.gated_worst_mm);
  };
  for (const auto& v : variants) {
    measure(views, v.detect);  // warm-up (allocations, caches)
    print(v.name, measure(views, v.detect));
  }
  // Hand-written vs net, interleaved five times so a change of machine load hits both alike.
  double hand_ms = 0, net_ms = 0;
  for (int round = 0; round < 5; ++round) {
    const Figures h = measure(views, variants[0].detect), n = measure(views, variants[1].detect);
    hand_ms += h.cpu_ms;
    net_ms += n.cpu_ms;
  }
  std::printf("hand-written vs net, 5 interleaved rounds: %.2f vs %.2f ms CPU per image (net / hand-written = %.3f)\n",
              hand_ms / (5.0 * views.size()), net_ms / (5.0 * views.size()), net_ms / hand_ms);
  return 0;
}
