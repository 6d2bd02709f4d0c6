// `imagenets calibration-plan`: what a calibration plan's poses will determine, before the robot
// moves: per estimated parameter its prior and predicted posterior standard deviation
// (predictObservability at the nominal robot), the parameters left
// unobservable, the condition number and the fixed point's predicted 3-sigma bound.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "imagenets/tool/command.h"
#include "imagenets_calibration/bundle_adjustment.h"

namespace imagenets {
namespace tool {
namespace {

// Translations are named "... x|y|z"; rotations "... rx|ry|rz" and joint offsets are angles.
bool isTranslation(const std::string& name) {
  const std::string last = name.substr(name.rfind(' ') + 1);
  return last == "x" || last == "y" || last == "z";
}

void declare(Flags& f) {
  f.add()("description", po::value<std::string>()->default_value(""), "the robot's description YAML (required)")
      ("camera", po::value<std::string>()->default_value(""), "stereo or mono: the calibration camera (default: the description's)")
      ("method", po::value<std::string>()->default_value("joint"), "joint or paper")
      ("loops", po::value<int>()->default_value(5), "loops of the plan")
      ("poses-per-loop", po::value<int>()->default_value(2), "poses per loop of the joint method")
      ("poses", po::value<int>()->default_value(0), "this many poses instead (0: loops x poses per loop)")
      ("noise", po::value<double>()->default_value(0.05), "image point noise in px")
      ("list", po::bool_switch(), "list every pose");
}

int calibrationPlan(const Options& flags) {
  const std::string method = flags["method"].as<std::string>(), description = flags["description"].as<std::string>();
  const int loops = flags["loops"].as<int>(), poses_per_loop = flags["poses-per-loop"].as<int>();
  const int poses = flags["poses"].as<int>();
  const double noise = flags["noise"].as<double>();
  const bool list = flags["list"].as<bool>();
  if (method != "joint" && method != "paper") throw UsageError("--method '" + method + "': expected joint or paper");
  if (loops < 1 || poses_per_loop < 1 || poses < 0) throw UsageError("--loops and --poses-per-loop must be >= 1, --poses >= 0");
  if (!(noise > 0)) throw UsageError("--noise must be positive (px)");
  const int count = poses > 0 ? poses : loops * (method == "joint" ? poses_per_loop : 1);
  if (description.empty()) throw UsageError("--description FILE is required (the robot's description YAML)");
  auto d = robot_description::loadRobotDescription(description);
  const std::string camera = flags["camera"].as<std::string>();
  if (!camera.empty()) {
    try {
      d = robot_description::withCalibrationCamera(d, camera, "--camera");
    } catch (const std::runtime_error& e) {
      throw UsageError(e.what());
    }
  }
  const imagenets_calibration::RobotModel model(d);
  std::string why;
  const auto cameras = imagenets_calibration::cameraModelsOf(model.description(), &why);
  if (!cameras) throw std::runtime_error("no camera model in the robot description: " + why);
  const auto plan = imagenets_calibration::calibrationPoses(model, count, method);
  const auto o = imagenets_calibration::predictObservability(model, *cameras, plan, noise);
  std::printf("calibration plan: method %s, %d poses, %s camera; predicted at the nominal robot with %.3g px point noise\n",
              method.c_str(), count, model.description().calibration_camera.c_str(), noise);
  if (list) {
    // Each pose: joints, where the marker centre is in the (first) calibration camera's image, how far, how oblique.
    const auto& first = cameras->cameras.front();
    for (size_t k = 0; k < plan.size(); ++k) {
      const Eigen::Isometry3d m = model.calibrationCamera(plan[k].head).inverse() * model.marker(plan[k].arm);
      const Eigen::Vector2d uv = first.model.project(m.translation());
      const double oblique = std::acos(std::min(1.0, -m.linear().col(2).dot(m.translation().normalized())));
      std::printf("pose %2zu: arm [", k);
      for (double q : plan[k].arm) std::printf(" %6.1f", q * 180 / M_PI);
      std::printf(" ] head [");  // empty for a camera on a stand
      for (double q : plan[k].head) std::printf(" %6.1f", q * 180 / M_PI);
      std::printf(" ] deg; marker at (%4.0f, %4.0f) px, %.3f m, %4.1f deg oblique\n", uv.x(), uv.y(),
                  m.translation().norm(), oblique * 180 / M_PI);
    }
  }
  if (!o.computed()) {
    std::printf("fewer than 3 views show the whole marker: nothing to fit\n");
    return 1;
  }
  std::printf("%-24s %12s %12s %16s\n", "parameter", "prior", "posterior", "posterior/prior");
  for (const auto& p : o.parameters) {
    const bool t = isTranslation(p.name);
    const double scale = t ? 1000.0 : 180.0 / M_PI;
    std::printf("%-24s %9.3f %-3s %9.4f %-3s %10.3f%s\n", p.name.c_str(), p.prior_std * scale, t ? "mm" : "deg",
                p.posterior_std * scale, t ? "mm" : "deg", p.posterior_std / p.prior_std,
                p.observable() ? "" : "  NOT OBSERVABLE");
  }
  const double sigma_t = std::sqrt(o.covariance.block<3, 3>(0, 0).trace());
  const double sigma_r = std::sqrt(o.covariance.block<3, 3>(3, 3).trace());
  std::printf("fixed point, predicted 3 sigma (3 sqrt(trace)): %.3f mm, %.4f deg\n", 3000 * sigma_t,
              3 * sigma_r * 180 / M_PI);
  std::printf("%s\n", o.summary().c_str());
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(calibration_plan, "calibration-plan",
                       "calibration-plan --description FILE [--camera stereo|mono] [--method joint|paper] [--loops N] [--poses-per-loop K] [--poses N] "
                       "[--noise PX] [--list]",
                       "what a calibration plan's poses will determine: per parameter prior vs predicted posterior, "
                       "unobservable ones, condition number",
                       declare, calibrationPlan);

}  // namespace tool
}  // namespace imagenets

// A program of its own, `imagenets-NAME`, run as `imagenets NAME`.
int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
