// bench_calibration_detection: what one calibration sample costs in image processing -- the
// robust marker detection (marker_measurement.h) of the left and right image -- and how accurate
// it is, on the simulator's own renderings of the joint method's ten poses (true geometry, default
// noise), then again with a spurious reflection near the marker in about half of the views.
// Compared: the calibration's detection (Otsu threshold first, the coarse-to-fine sweep only when
// that is not good), always sweeping, an exhaustive sweep, a single fixed threshold (no feedback)
// and the whole image instead of the predicted region. Times are CPU time of the detecting thread (robust to a loaded
// machine) and wall time of a left+right pair detected in parallel, as the node does.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <future>
#include <random>
#include <string>
#include <vector>

#include <camera_calibration_parsers/parse.h>

#include "friend_hw_sim/true_robot.h"
#include "friend_calibration/calibration.h"
#include "friend_calibration/marker_measurement.h"
#include "friend_hw_sim/cameras.h"
#include "robot_description/robot_model.h"
#include "imagenets/blocks/marker.h"

using namespace friend_calibration;
namespace render = imagenets::render;
using Clock = std::chrono::steady_clock;

namespace {

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

struct View {
  cv::Mat image;
  sensor_msgs::CameraInfo info;
  Eigen::Isometry3d truth, predicted;  // T_camera_marker
  bool reflection = false;
};

// Accuracy is counted apart for clean views and for views with a reflection whose detection
// passes the calibration's reprojection gate (FusionLimits::min_reprojection_error, the limit
// for this camera's noise): a disturbed detection the gate lets through is what biases a result.
struct Figures {
  double cpu_ms = 0, pair_wall_ms = 0, clean_worst_mm = 0, clean_sum_mm = 0, clean_sum_deg = 0, gated_worst_mm = 0;
  int clean = 0, clean_found = 0, disturbed = 0, disturbed_found = 0, disturbed_passed = 0;
};

Figures measure(const std::vector<View>& views, const imagenets::marker::MarkerDescription& marker,
                const RobustDetectionOptions& options) {
  Figures f;
  auto one = [&](const View& v, double* cpu) {
    const double c0 = threadCpuMs();
    MarkerObservation o = detectMarkerRobustly(v.image, v.info, marker, v.predicted, options);
    *cpu = threadCpuMs() - c0;
    return o;
  };
  for (size_t i = 0; i + 1 < views.size(); i += 2) {  // left, right of one pose
    double cpu_l = 0, cpu_r = 0;
    const auto t0 = Clock::now();
    auto right = std::async(std::launch::async, one, views[i + 1], &cpu_r);
    const MarkerObservation left = one(views[i], &cpu_l);
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
  const std::string desc_path = robot_description::defaultRobotDescriptionPath();
  const std::string root = desc_path.substr(0, desc_path.size() - std::string("config/friend/robot.yaml").size());
  const auto nominal_desc = robot_description::loadRobotDescription(desc_path);
  const RobotModel nominal(nominal_desc);
  const RobotModel truth(friend_hw_sim::applyTrueError(
      nominal_desc, friend_hw_sim::loadTrueError(root + "config/friend/true_error.yaml")));
  const auto world = friend_hw_sim::loadWorldScene(root + "config/friend/scene.yaml");
  const auto marker = imagenets::marker::MarkerDescription::load(root + "config/markers/gripper.yaml");
  const render::Plane plane = imagenets::marker::markerPlane(marker, Eigen::Isometry3d::Identity());
  sensor_msgs::CameraInfo info[2];
  std::string name;
  camera_calibration_parsers::readCalibration(nominal_desc.left_camera_info, name, info[0]);
  camera_calibration_parsers::readCalibration(nominal_desc.right_camera_info, name, info[1]);
  const render::Renderer renderer[2] = {render::Renderer(render::CameraModel::fromCameraInfo(info[0]), 2),
                                        render::Renderer(render::CameraModel::fromCameraInfo(info[1]), 2)};

  // The joint method's ten poses, twice: clean, and with a reflection in every other view.
  std::vector<View> views;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const auto poses = calibrationPoses(nominal, 10, "joint");
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& p : poses) {
      for (int side = 0; side < 2; ++side) {
        View v;
        v.info = info[side];
        const Eigen::Isometry3d cam_true = side == 0 ? truth.leftCamera(p.head) : truth.rightCamera(p.head);
        const Eigen::Isometry3d cam_nominal = side == 0 ? nominal.leftCamera(p.head) : nominal.rightCamera(p.head);
        v.truth = cam_true.inverse() * truth.marker(p.arm);
        v.predicted = cam_nominal.inverse() * nominal.marker(p.arm);
        render::RenderOptions o;
        o.noise_sigma = 1.5;
        o.blur_sigma = 0.6;
        o.background = 0.5;
        o.seed = static_cast<int>(views.size()) + 1;
        v.image = friend_hw_sim::renderView(renderer[side], world, plane, truth.marker(p.arm), cam_true, o);
        if (pass == 1 && u(rng) < 0.5) {
          // As the simulator's reflection fault: a third of the marker's size, within one side of it.
          const double side_px = info[side].K[0] * marker.size / v.truth.translation().z();
          const cv::Point2d c = renderer[side].camera().project(v.truth.translation());
          friend_hw_sim::addSpecularHighlight(v.image, c + cv::Point2d((u(rng) - 0.5) * side_px, (u(rng) - 0.5) * side_px),
                                              side_px * (0.12 + 0.15 * u(rng)), 200 + 100 * u(rng));
          v.reflection = true;
        }
        views.push_back(v);
      }
    }
  }
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
    const char* name;
    RobustDetectionOptions options;
  };
  std::vector<Variant> variants;
  variants.push_back({"calibration default (Otsu first, stop if good)", RobustDetectionOptions()});
  RobustDetectionOptions always_sweep;
  always_sweep.good_confidence = 0;
  variants.push_back({"always the coarse-to-fine sweep", always_sweep});
  RobustDetectionOptions exhaustive;
  exhaustive.coarse_from = 20;
  exhaustive.coarse_to = 235;
  exhaustive.coarse_step = 5;
  exhaustive.fine_step = 0;
  exhaustive.good_confidence = 0;
  variants.push_back({"exhaustive 20..235 step 5", exhaustive});
  RobustDetectionOptions fixed = always_sweep;
  fixed.coarse_from = fixed.coarse_to = 120;
  fixed.fine_step = 0;
  variants.push_back({"fixed threshold 120 (no feedback)", fixed});
  RobustDetectionOptions whole = always_sweep;
  whole.roi_margin_px = 0;
  variants.push_back({"always sweep, whole image (no ROI)", whole});
  for (const auto& v : variants) {
    measure(views, marker, v.options);  // warm-up (allocations, caches)
    const Figures f = measure(views, marker, v.options);
    const int views = f.clean + f.disturbed;
    std::printf("%-48s %10.2f %12.2f | %4d / %-5d %7.3f %8.4f %8.3f | %4d / %-5d %-6d %8.3f\n", v.name,
                f.cpu_ms / views, f.pair_wall_ms / (views / 2), f.clean_found, f.clean,
                f.clean_found ? f.clean_sum_mm / f.clean_found : 0, f.clean_found ? f.clean_sum_deg / f.clean_found : 0,
                f.clean_worst_mm, f.disturbed_found, f.disturbed, f.disturbed_passed, f.gated_worst_mm);
  }
  return 0;
}
