// bench_calibration_detection: what one calibration sample costs in image processing -- the
// robust marker detection net (config/nets/calibration_marker_detection.yaml) of the left and
// right image -- and how accurate it is, on the simulator's own renderings of the joint method's
// ten poses (true geometry, default noise), then again with a spurious reflection near the marker
// in about half of the views (friend_calibration/test/calibration_views.h).
// Compared: the calibration's detection (Otsu threshold first, stop when good, else the
// coarse-to-fine sweep), then the same net with its feedback changed: always sweeping, an
// exhaustive sweep, a single fixed threshold (no feedback) and the whole image instead of the
// predicted region. Times are CPU time of the detecting thread (robust to a loaded machine; the
// net runs on an executor with one thread, the caller's) and wall time of a left+right pair
// detected in parallel, as the node does.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <functional>
#include <map>
#include <future>
#include <string>
#include <vector>

#include "calibration_views.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/calibration_marker_net.h"
#include "imagenets/bench_summary.h"
#include "imagenets/blocks/image.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/time.h"

using namespace imagenets_calibration;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kDefault = "calibration default (Otsu first, stop if good)";

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
    const double c0 = imagenets::threadCpuMs();
    MarkerObservation o = detect(v, side);
    *cpu = imagenets::threadCpuMs() - c0;
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

using Variant = std::pair<std::string, Detect>;

// The views as the node receives them (ROS messages, converted before timing) and one net per
// camera for each variant.
struct Variants {
  const std::vector<CalibrationView>& views;
  std::vector<sensor_msgs::ImageConstPtr> messages;
  std::vector<std::unique_ptr<CalibrationMarkerNet>> nets;

  explicit Variants(const std::vector<CalibrationView>& v) : views(v) {
    for (const auto& view : views) messages.push_back(imagenets::blocks::toImageMsg(view.image, "mono8", view.info.header));
  }

  // The shipped net with its threshold search changed and, if given, other region margins tried
  // (0 = the whole image) and the search's detector given other properties; one net per camera,
  // in parallel.
  Detect variant(const std::function<void(imagenets::FeedbackSpec&)>& change, bool use_prediction,
                 std::vector<double> region_margins_px = {},
                 const std::map<std::string, std::string>& detector_properties = {}) {
    imagenets::NetSpec spec = CalibrationMarkerNet::specWithSearch([&](imagenets::NetSpec& search) {
      for (auto& b : search.blocks) {
        if (b.feedback) change(*b.feedback);
      }
      for (const auto& [name, text] : detector_properties) search.block("detector").setProperty(name, text);
    });
    for (auto& b : spec.blocks) {
      if (b.feedback && !region_margins_px.empty()) b.feedback->values = region_margins_px;
    }
    CalibrationMarkerNet* pair[2];
    for (auto*& net : pair) {
      nets.push_back(std::make_unique<CalibrationMarkerNet>(spec, 1));
      net = nets.back().get();
    }
    return [this, pair, use_prediction](const CalibrationView& v, int side) {
      return pair[side]->detect(messages[&v - views.data()], v.info,
                                use_prediction ? std::optional<Eigen::Isometry3d>(v.predicted) : std::nullopt);
    };
  }
};

// The threshold grid tried downwards from `from` (after Otsu): a reflection brightens part of the
// marker's border, which then stays dark only under a high threshold.
std::function<void(imagenets::FeedbackSpec&)> downwardsFrom(double from) {
  return [from](imagenets::FeedbackSpec& f) {
    f.to = std::min(*f.from, *f.to);
    f.from = from;
    f.values.clear();
    for (double v = from; v >= *f.to - 1e-9; v -= *f.step) f.values.push_back(v);
  };
}

// Candidates given as a list, tried in order, no first guess, no early stop.
std::function<void(imagenets::FeedbackSpec&)> only(std::vector<double> values) {
  return [values](imagenets::FeedbackSpec& f) {
    f.good_enough.reset();
    f.initial.clear();
    f.search = "exhaustive";
    f.coarse_step.reset();
    f.fine_radius.reset();
    f.from.reset();
    f.to.reset();
    f.step.reset();
    f.values = values;
  };
}

// The calibration's own detection first, then the same net with its search or region changed.
std::vector<Variant> makeVariants(Variants& v) {
  auto always_sweep = [](imagenets::FeedbackSpec& f) { f.good_enough.reset(); };
  const auto unchanged = [](imagenets::FeedbackSpec&) {};
  std::vector<double> every5;
  for (int t = 20; t <= 235; t += 5) every5.push_back(t);
  return {
      {kDefault, v.variant(unchanged, true)},
      // Its region: 120 px around the prediction, the whole image only where that misses the
      // marker; a wider first region, and always the whole image.
      {"region 300 px, else the whole image", v.variant(unchanged, true, {300, 0})},
      {"region always the whole image", v.variant(unchanged, true, {0})},
      // Every quadrilateral examined, also those under half the predicted marker's size.
      {"small quadrilaterals examined too", v.variant(unchanged, true, {}, {{"min_side_of_hint", "0"}})},
      {"always the coarse-to-fine sweep", v.variant(always_sweep, true)},
      {"grid downwards 190..10 (Otsu first, stop if good)", v.variant(downwardsFrom(190), true)},
      {"grid downwards 220..10 (Otsu first, stop if good)", v.variant(downwardsFrom(220), true)},
      {"exhaustive 20..235 step 5", v.variant(only(every5), true)},
      {"fixed threshold 120 (no search)", v.variant(only({120}), true)},
      {"always sweep, whole image (no ROI, no pose hint)", v.variant(always_sweep, false)},
  };
}

void printHeader(const std::vector<CalibrationView>& views) {
  int reflections = 0;
  for (const auto& v : views) reflections += v.reflection;
  std::printf("robust marker detection for the calibration: %zu views of 1024x768 (10 joint-method poses x left/right,\n"
              "twice; %d with a spurious reflection), region of interest from the nominal prediction;\n"
              "errors against the true marker pose in the camera frame; 'passed': reflection-disturbed detections\n"
              "with a reprojection error within the calibration's gate (%.2f px)\n",
              views.size(), reflections, FusionLimits().min_reprojection_error);
  std::printf("%-48s %10s %12s | %-12s %7s %8s %8s | %-12s %-6s %8s\n", "sweep", "CPU ms/img", "pair wall ms",
              "clean found", "mean mm", "mean deg", "worst mm", "refl. found", "passed", "worst mm");
}

void printRow(const std::string& name, const Figures& f) {
  const int views = f.clean + f.disturbed;
  std::printf("%-48s %10.2f %12.2f | %4d / %-5d %7.3f %8.4f %8.3f | %4d / %-5d %-6d %8.3f\n", name.c_str(),
              f.cpu_ms / views, f.pair_wall_ms / (views / 2), f.clean_found, f.clean,
              f.clean_found ? f.clean_sum_mm / f.clean_found : 0, f.clean_found ? f.clean_sum_deg / f.clean_found : 0,
              f.clean_worst_mm, f.disturbed_found, f.disturbed, f.disturbed_passed, f.gated_worst_mm);
  if (name != kDefault) return;
  // Per image, as the column above and the hand-written detection's old 6.94 ms figure.
  const double image_cpu = f.cpu_ms / views;
  imagenets::printSummaryRow("calibration detection, CPU ms per image (the calibration's net)", image_cpu, NAN,
                             "<= 8 ms", image_cpu <= 8);
  imagenets::printSummaryRow("calibration detection, wall ms per stereo pair (left, right in parallel)",
                             f.pair_wall_ms / (views / 2), NAN, "", false);
  imagenets::printSummaryRow("calibration detection, clean views found", f.clean_found, f.clean, "all",
                             f.clean_found == f.clean);
}

}  // namespace

// Arguments (optional): run only the variants whose name contains the first, and measure each the
// second times (for a profiler: `perf record -D 6000 ... bench_calibration_detection default 20`).
int main(int argc, char** argv) {
  const char* only_variant = argc > 1 ? argv[1] : nullptr;
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 1;
  const CalibrationViews data = renderCalibrationViews();
  printHeader(data.views);
  Variants variants(data.views);
  for (const auto& [name, detect] : makeVariants(variants)) {
    if (only_variant && name.find(only_variant) == std::string::npos) continue;
    measure(data.views, detect);  // warm-up (allocations, caches)
    for (int r = 1; r < repeats; ++r) measure(data.views, detect);
    printRow(name, measure(data.views, detect));
  }
  return 0;
}
