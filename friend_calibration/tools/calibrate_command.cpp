// `imagenets calibrate`: triggers the running friend_calibration node, prints the fixed point and,
// against the simulator, its error against the true one.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "calibration_client.h"
#include "imagenets/tool/command.h"
#include "robot_description/robot_model.h"

namespace imagenets {
namespace tool {
namespace {

int calibrate(const Args& args) {
  int redundancy = 5, poses = 0, max_poses = 0;
  std::string method;
  double timeout = 30, target_mm = 0, target_deg = 0;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--redundancy") {
      redundancy = intValue(args, i);
    } else if (args[i] == "--poses") {
      poses = intValue(args, i);
    } else if (args[i] == "--target-mm") {
      target_mm = doubleValue(args, i);
    } else if (args[i] == "--target-deg") {
      target_deg = doubleValue(args, i);
    } else if (args[i] == "--max-poses") {
      max_poses = intValue(args, i);
    } else if (args[i] == "--method") {
      method = flagValue(args, i);
    } else if (args[i] == "--wait") {
      timeout = doubleValue(args, i);
    } else if (args[i].rfind("__", 0) != 0) {  // roslaunch's __name:= etc.
      throw unknownArgument(args[i]);
    }
  }
  if (poses < 0) throw UsageError("--poses must be >= 0");
  CalibrationClient client("imagenets_calibrate", timeout);
  imagenets_calibration_msgs::Calibrate::Request request;
  request.redundancy = redundancy;
  request.method = method;
  request.poses = poses;
  // The node names a bad value (negative target, ...) in its answer.
  request.target_uncertainty = target_mm / 1000;
  request.target_uncertainty_rotation = target_deg * M_PI / 180;
  request.max_poses = max_poses;
  const CalibrationRun run = client.calibrate(request);
  const auto& r = run.response;
  std::printf("%s: %s\n", r.success ? "calibrated" : "FAILED", r.message.c_str());
  if (!r.success) return 1;
  const auto& t = r.fixed_point.transform.translation;
  const Eigen::Vector3d rpy = robot_description::rpyOf(run.fixed_point.rotation()) * 180 / M_PI;
  std::printf("fixed point %s -> %s: xyz [%.4f %.4f %.4f] m, rpy [%.3f %.3f %.3f] deg\n",
              r.fixed_point.header.frame_id.c_str(), r.fixed_point.child_frame_id.c_str(), t.x, t.y, t.z, rpy.x(),
              rpy.y(), rpy.z());
  std::printf("spread (std dev) x y z: %.3f %.3f %.3f mm, rotation %.4f %.4f %.4f deg; samples used %d, rejected %d\n",
              r.std_dev_translation.x * 1000, r.std_dev_translation.y * 1000, r.std_dev_translation.z * 1000,
              r.std_dev_rotation.x * 180 / M_PI, r.std_dev_rotation.y * 180 / M_PI, r.std_dev_rotation.z * 180 / M_PI,
              r.samples_used, r.samples_rejected);
  if (run.bound3_mm > 0) {
    std::printf("uncertainty of the pixel-level fit (3 sigma = 3 sqrt(trace)): %.3f mm, %.4f deg\n", run.bound3_mm,
                run.bound3_deg);
  }
  if (r.condition_number > 0) {
    std::string names;
    for (const auto& n : r.unobservable) names += (names.empty() ? "" : ", ") + n;
    std::printf("observability: condition number %.3g; %s\n", r.condition_number,
                names.empty() ? "every estimated parameter observable" : ("not observable from these poses: " + names).c_str());
  }
  if (target_mm > 0 || target_deg > 0) {
    std::printf("uncertainty target (%.3f mm, %.4f deg; 0 = none) %s after %d poses\n", target_mm, target_deg,
                r.target_met ? "met" : "NOT met", r.poses_taken);
  }
  std::printf("time: %.3f s compute, %.2f s with motion\n", r.compute_time, r.total_time);
  if (run.have_truth) {
    std::printf("error against the simulator's true head mount: %.3f mm, %.4f deg\n", run.error_mm, run.error_deg);
    std::printf("error against the effective fixed point (true mount with the pan encoder's zero offset, which no "
                "calibration of this frame can separate): %.3f mm, %.4f deg\n",
                run.effective_error_mm, run.effective_error_deg);
    std::printf("error against the identifiable fixed point (arm joint 1's zero offset folded in as well: a turn of "
                "the whole arm about its first axis, which no calibration from the arm's marker can tell from a turn "
                "of the head mount): %.3f mm, %.4f deg\n",
                run.identifiable_error_mm, run.identifiable_error_deg);
  }
  std::printf("calibration file: %s\n", r.file.c_str());
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(calibrate, "calibrate", "calibrate [--redundancy N] [--poses N] [--method paper|joint] [--target-mm MM] [--target-deg DEG] "
                       "[--max-poses N] [--wait S]",
                       "trigger the running friend_calibration node; print the fixed point (and its error in simulation); "
                       "--target-mm/--target-deg: more poses until the 3-sigma bound is within",
                       calibrate);

}  // namespace tool
}  // namespace imagenets

// A program of its own, `imagenets-NAME`, run as `imagenets NAME`.
int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
