// `imagenets calibrate`: triggers the running friend_calibration node, prints the fixed point and,
// against the simulator, its error against the true one. With --bag: calibrates from a rosbag
// offline, without robot or master (imagenets_calibration/bag_calibration.h), for any robot.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "calibration_client.h"
#include "imagenets/tool/command.h"
#include "imagenets_calibration/bag_calibration.h"
#include "imagenets_calibration/storage.h"
#include "robot_description/robot_model.h"
#include "robot_description/urdf_kinematics.h"

namespace imagenets {
namespace tool {
namespace {

// --bag: the calibration net on the bag's samples; the result (and the calibrated URDF beside it)
// written to --output only when it succeeds, so a failed run leaves a previous file as it was.
int calibrateFromBag(const imagenets_calibration::BagCalibrationOptions& options, const std::string& output) {
  imagenets_calibration::BagCalibration c;
  try {
    c = imagenets_calibration::calibrateFromBag(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "calibration from the bag failed: %s%s\n", e.what(),
                 output.empty() ? "" : ("; " + output + " is unchanged").c_str());
    return 1;
  }
  const auto& r = c.result;
  std::printf("bag: %s\n", c.samples.c_str());
  std::printf("%s: %s\n", r.success ? "calibrated" : "FAILED", r.message.c_str());
  for (size_t i = 0; i < r.rejected.size(); ++i) {
    std::printf("sample %d not used: %s\n", r.rejected[i],
                i < r.rejection_reasons.size() ? r.rejection_reasons[i].c_str() : "");
  }
  if (!r.success) {
    if (!output.empty()) std::printf("%s is unchanged\n", output.c_str());
    return 1;
  }
  const Eigen::Vector3d t = r.fixed_point.translation();
  const Eigen::Vector3d rpy = robot_description::rpyOf(r.fixed_point.rotation()) * 180 / M_PI;
  std::printf("fixed point: xyz [%.6f %.6f %.6f] m, rpy [%.5f %.5f %.5f] deg; %zu samples used, %zu rejected\n", t.x(),
              t.y(), t.z(), rpy.x(), rpy.y(), rpy.z(), r.used.size(), r.rejected.size());
  if (r.has_covariance) {
    std::printf("uncertainty of the pixel-level fit (3 sigma = 3 sqrt(trace)): %.3f mm, %.4f deg\n",
                3000 * r.sigmaTranslation(), 3 * r.sigmaRotation() * 180 / M_PI);
  }
  if (!output.empty()) {
    const robot_description::RobotModel model(robot_description::loadRobotDescription(options.description));
    imagenets_calibration::StoredCalibration stored;
    stored.base_frame = model.description().base_frame;
    stored.result = r;
    imagenets_calibration::saveCalibration(stored, output);
    stored.file = output;
    const std::string urdf = imagenets_calibration::urdfFileBeside(output);
    imagenets_calibration::saveCalibratedUrdf(model, stored, urdf);
    std::printf("calibration file: %s; calibrated URDF: %s\n", output.c_str(), urdf.c_str());
  }
  return 0;
}

// What the node answered, and against the simulator the errors against its truth.
int printRun(const CalibrationRun& run, double target_mm, double target_deg) {
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


void declare(Flags& f) {
  f.add()("redundancy", po::value<int>()->default_value(5), "loops of the calibration")
      ("poses", po::value<int>()->default_value(0), "poses to take (0: the plan's)")
      ("method", po::value<std::string>()->default_value(""), "paper or joint (default: the node's)")
      ("target-mm", po::value<double>()->default_value(0), "take poses until the 3-sigma bound is this small (mm)")
      ("target-deg", po::value<double>()->default_value(0), "... and this small (deg)")
      ("max-poses", po::value<int>()->default_value(0), "at most this many poses for a target (0: the node's)")
      ("wait", po::value<double>()->default_value(30), "seconds to wait for the calibration node")
      ("bag", po::value<std::string>()->default_value(""), "calibrate offline from this rosbag instead")
      ("config", po::value<std::string>()->default_value(""), "with --bag: the robot's description YAML")
      ("urdf", po::value<std::string>()->default_value(""), "with --bag: the robot's URDF when the config names none")
      ("net", po::value<std::string>()->default_value(""), "with --bag: the calibration net")
      ("set", po::value<std::vector<std::string>>(), "with --bag: PROPERTY=VALUE for every block that has it")
      ("output,o", po::value<std::string>()->default_value(""), "with --bag: write the calibration here");
  f.acceptRosArguments();
}

// --bag and what goes with it.
int calibrateBag(const Options& o) {
  imagenets_calibration::BagCalibrationOptions bag;
  bag.bag = o["bag"].as<std::string>();
  bag.description = o["config"].as<std::string>();
  bag.net = o["net"].as<std::string>();
  for (const auto& s : strings(o, "set")) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("--set '" + s + "' is not property=value");
    bag.settings.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  if (bag.description.empty()) throw UsageError("--bag needs --config FILE (the robot's description YAML)");
  if (!o["urdf"].as<std::string>().empty()) robot_description::useUrdfFile(o["urdf"].as<std::string>());
  if (!o["method"].as<std::string>().empty()) bag.method = o["method"].as<std::string>();
  return calibrateFromBag(bag, o["output"].as<std::string>());
}

int calibrate(const Options& o) {
  if (!o["bag"].as<std::string>().empty()) return calibrateBag(o);
  if (!o["config"].as<std::string>().empty() || !o["net"].as<std::string>().empty() ||
      !o["output"].as<std::string>().empty() || o.count("set") || !o["urdf"].as<std::string>().empty()) {
    throw UsageError("--config, --urdf, --net, --output and --set go with --bag");
  }
  const int poses = o["poses"].as<int>();
  if (poses < 0) throw UsageError("--poses must be >= 0");
  const double target_mm = o["target-mm"].as<double>(), target_deg = o["target-deg"].as<double>();
  CalibrationClient client("imagenets_calibrate", o["wait"].as<double>());
  imagenets_calibration_msgs::Calibrate::Request request;
  request.redundancy = o["redundancy"].as<int>();
  request.method = o["method"].as<std::string>();
  request.poses = poses;
  // The node names a bad value (negative target, ...) in its answer.
  request.target_uncertainty = target_mm / 1000;
  request.target_uncertainty_rotation = target_deg * M_PI / 180;
  request.max_poses = o["max-poses"].as<int>();
  return printRun(client.calibrate(request), target_mm, target_deg);
}

}  // namespace

IMAGENETS_TOOL_COMMAND(calibrate, "calibrate", "calibrate [--redundancy N] [--poses N] [--method paper|joint] [--target-mm MM] [--target-deg DEG] "
                       "[--max-poses N] [--wait S] | calibrate --bag FILE.bag --config ROBOT.yaml [--urdf FILE] [--net FILE] "
                       "[--method paper|joint] [--set PROPERTY=VALUE ...] [--output FILE.yaml]",
                       "trigger the running friend_calibration node; print the fixed point (and its error in simulation); "
                       "--target-mm/--target-deg: more poses until the 3-sigma bound is within; --bag: calibrate offline "
                       "from a rosbag (no robot, no master), the samples where arm and head stood still; --urdf: the robot's URDF "
                       "when the config names none",
                       declare, calibrate);

}  // namespace tool
}  // namespace imagenets

// A program of its own, `imagenets-NAME`, run as `imagenets NAME`.
int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
