// bench_calibration_solvers: the joint calibration solved two ways on the same detections, side by
// side -- today's joint least squares over 3D marker points (each detection's own pose) and the
// pixel-level bundle adjustment (Ceres) that now refines it -- error against the simulator's truth
// (the effective fixed point: the true mount turned by the pan encoder's zero offset), the
// reported 3-sigma bound, and compute time per pose. Detections: the calibration's marker
// detection net on the simulator's renderings of the joint method's ten poses, clean and with a
// reflection in about half of the views (friend_calibration/test/calibration_views.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calibration_views.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/calibration_marker_net.h"
#include "friend_hw_sim/true_robot.h"
#include "imagenets/blocks/image.h"
#include "imagenets/package_file.h"
#include "imagenets/bench_summary.h"

using namespace imagenets_calibration;
using Clock = std::chrono::steady_clock;

int main() {
  const std::string desc_path = imagenets::packageFile("friend_description", "config/robot.yaml");
  const auto nominal_desc = robot_description::loadRobotDescription(desc_path);
  const RobotModel model(nominal_desc);
  const auto error = friend_hw_sim::loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), nominal_desc);
  const RobotModel truth(friend_hw_sim::applyTrueError(nominal_desc, error));
  const Eigen::Isometry3d effective = friend_hw_sim::effectiveHeadBase(nominal_desc, error);
  // What images can determine at all: arm joint 1's zero offset folded in as well.
  const Eigen::Isometry3d identifiable = friend_hw_sim::identifiableHeadBase(nominal_desc, error);

  const CalibrationViews views = renderCalibrationViews();
  const auto poses = calibrationPoses(model, 10, "joint");
  CalibrationMarkerNet net[2];
  std::vector<Sample> sets[2];
  for (size_t k = 0; k + 1 < views.views.size(); k += 2) {
    const size_t pose = (k / 2) % poses.size();
    Sample s;
    s.arm_q = poses[pose].arm;
    s.head_q = poses[pose].head;
    for (int side = 0; side < 2; ++side) {
      const CalibrationView& v = views.views[k + side];
      (side == 0 ? s.left : s.right) =
          net[side].detect(imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header), v.info, v.predicted);
    }
    sets[k / 2 / poses.size()].push_back(s);
  }

  std::printf("joint calibration, 10 poses, detections of the simulator's renderings (true robot of true_error.yaml);\n"
              "error against the effective fixed point (true mount, pan offset folded in) and the identifiable one\n"
              "(arm joint 1 offset folded in too); 3 sigma = 3 sqrt(trace) of the reported covariance;\n"
              "time = compute per pose (median of 5 runs)\n");
  std::printf("%-12s %-18s %9s %9s %9s %9s %10s %10s %8s\n", "images", "solver", "eff. mm", "eff. deg", "ident. mm",
              "ident.deg", "3sigma mm", "3sigma deg", "ms/pose");
  const char* names[2] = {"clean", "reflections"};
  for (int set = 0; set < 2; ++set) {
    const auto& samples = sets[set];
    for (int solver = 0; solver < 2; ++solver) {
      Result r;
      std::vector<double> ms;
      for (int run = 0; run < 5; ++run) {
        const auto t0 = Clock::now();
        if (solver == 0) {
          // Today's joint solve alone (calibrate() minus the refinement).
          r = solveJointly(model, calibrate(model, samples, "paper", FusionLimits(), CombineOptions()), FusionLimits());
        } else {
          r = calibrate(model, samples, "joint", FusionLimits(), CombineOptions());
        }
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / samples.size());
      }
      std::sort(ms.begin(), ms.end());
      if (!r.success) {
        std::printf("%-12s %-18s FAILED: %s\n", names[set], solver ? "pixel-level BA" : "joint (3D points)", r.message.c_str());
        continue;
      }
      char bound_t[32] = "-", bound_r[32] = "-";
      if (r.has_covariance) {
        std::snprintf(bound_t, sizeof bound_t, "%.3f", 3000 * r.sigmaTranslation());
        std::snprintf(bound_r, sizeof bound_r, "%.4f", 3 * r.sigmaRotation() * 180 / M_PI);
      }
      std::printf("%-12s %-18s %9.3f %9.4f %9.3f %9.4f %10s %10s %8.2f\n", names[set],
                  solver ? "pixel-level BA" : "joint (3D points)",
                  (r.fixed_point.translation() - effective.translation()).norm() * 1000,
                  angleBetween(r.fixed_point, effective) * 180 / M_PI,
                  (r.fixed_point.translation() - identifiable.translation()).norm() * 1000,
                  angleBetween(r.fixed_point, identifiable) * 180 / M_PI, bound_t, bound_r, ms[ms.size() / 2]);
      imagenets::printSummaryRow(std::string("calibration solve, effective-pose error mm: ") +
                                     (solver ? "pixel-level BA" : "joint (3D points)") + ", " + names[set] + " images",
                                 (r.fixed_point.translation() - effective.translation()).norm() * 1000, NAN, "", false);
    }
  }
  return 0;
}
