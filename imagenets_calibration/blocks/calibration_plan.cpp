// The plan of a FRIEND calibration (paper 4.2): the method, and per sample the calibration pose
// (calibrationPoses of calibration.h), or the stored file whose samples are replayed.
#include <boost/make_shared.hpp>

#include "calibration_ports.h"
#include "imagenets_calibration/storage.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class CalibrationPlan : public imagenets::Block {
 public:
  CalibrationPlan() {
    addOutput<imagenets_calibration_msgs::CalibrationPlan>("plan", "method, sample count, pose of every sample (or the replay file)");
    addOutput<std_msgs::Int32>("samples", "number of samples (the `repeat` of the sample sub-net)");
    addOutput<std_msgs::Int32>("max_samples", "with a target: at most this many samples (the sample sub-net's "
                                              "`max_repeat`); else = samples");
    addProperty<std::string>("method", "joint", "paper: the paper's method (4.2); joint: our least squares")
        .choices({"paper", "joint"});
    addProperty<int>("loops", 5, "the redundancy N (odd: the per-axis median is one of the samples)").range(1, 999);
    addProperty<int>("poses_per_loop", 2, "joint method: different poses per loop (its unknowns need them)")
        .range(1, 10);
    addProperty<int>("poses", 0, "number of samples; 0 = loops (paper) or loops x poses_per_loop (joint)")
        .range(0, 1000);
    addProperty<double>("target_uncertainty", 0.0,
                        "m: after `poses`, add the next poses until the fixed point's 3-sigma translation bound "
                        "is at most this (joint method; 0 = off)")
        .range(0.0, 1.0);
    addProperty<double>("target_uncertainty_rotation", 0.0, "rad: the same for the rotation bound (0 = off)")
        .range(0.0, M_PI);
    addProperty<int>("max_poses", 30, "with a target: at most this many samples in all").range(1, 1000);
    addProperty<double>("reapproach_deg", 10.0, "paper method: the arm comes to the pose anew from this far (joint 4)")
        .range(0.0, 45.0);
    addProperty<std::string>("replay", "", "a saved calibration file: replay its samples instead (no robot)").path();
    addProperty<std::string>("bag", "", "a rosbag: its still stereo pairs are the samples (no robot)").path();
    for (const auto& p : bagSampleProperties()) addPropertySpec(p);
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
    addPropertySpec(calibrationCameraProperty());
  }

  void process(imagenets::Context& ctx) override {
    auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
    plan->method = ctx.property<std::string>("method");
    plan->loops = ctx.property<int>("loops");
    plan->replay_file = ctx.property<std::string>("replay");
    plan->bag_file = ctx.property<std::string>("bag");
    if (!plan->replay_file.empty() && !plan->bag_file.empty()) {
      throw imagenets::BlockError("properties 'replay' and 'bag': set one of them, not both");
    }
    if (!plan->bag_file.empty()) {
      planBag(ctx, *plan);
    } else if (!plan->replay_file.empty()) {
      planReplay(*plan);
    } else {
      planPoses(ctx, *plan);
    }
    if (plan->max_samples < plan->samples) plan->max_samples = plan->samples;  // replay
    auto count = boost::make_shared<std_msgs::Int32>();
    count->data = plan->samples;
    auto max_count = boost::make_shared<std_msgs::Int32>();
    max_count->data = plan->max_samples;
    ctx.output("plan", plan);
    ctx.output("samples", count);
    ctx.output("max_samples", max_count);
  }

 private:
  // A bag's still stereo pairs are the samples.
  static void planBag(imagenets::Context& ctx, imagenets_calibration_msgs::CalibrationPlan& plan) {
    const RobotModel& model =
        robotModel(ctx.property<std::string>("description"), ctx.property<std::string>("calibration_camera"));
    try {
      const auto bag = readBagSamples(plan.bag_file, sampleJoints(model), bagSampleSettings(ctx));
      plan.samples = static_cast<int>(bag->samples.size());
    } catch (const std::exception& e) {
      throw imagenets::BlockError(std::string("property 'bag': ") + e.what());
    }
    if (plan.samples == 0) {
      throw imagenets::BlockError("property 'bag': no samples: " +
                                  readBagSamples(plan.bag_file, sampleJoints(model), bagSampleSettings(ctx))->report);
    }
  }

  // A saved calibration's samples are replayed.
  static void planReplay(imagenets_calibration_msgs::CalibrationPlan& plan) {
    try {
      plan.samples = static_cast<int>(loadCalibration(plan.replay_file).result.samples.size());
    } catch (const std::exception& e) {
      throw imagenets::BlockError(std::string("property 'replay': ") + e.what());
    }
    if (plan.samples == 0) throw imagenets::BlockError("property 'replay': " + plan.replay_file + " holds no samples");
  }

  // The robot moves: the sample count (and with a target the most samples), then every pose.
  static void planPoses(imagenets::Context& ctx, imagenets_calibration_msgs::CalibrationPlan& plan) {
    const int poses = ctx.property<int>("poses");
    if (poses == 0 && plan.loops % 2 == 0) {
      throw imagenets::BlockError("property 'loops': redundancy must be odd and >= 1 (the per-axis median needs a "
                                  "middle value), got " + std::to_string(plan.loops));
    }
    if (poses > 0 && plan.method == "paper" && poses % 2 == 0) {
      throw imagenets::BlockError("property 'poses': the paper method's samples must be odd (the per-axis median "
                                  "needs a middle value), got " + std::to_string(poses));
    }
    const RobotModel& model =
        robotModel(ctx.property<std::string>("description"), ctx.property<std::string>("calibration_camera"));
    plan.samples = poses > 0 ? poses : plan.loops * (plan.method == "joint" ? ctx.property<int>("poses_per_loop") : 1);
    plan.max_samples = plan.samples;
    plan.target_uncertainty = ctx.property<double>("target_uncertainty");
    plan.target_uncertainty_rotation = ctx.property<double>("target_uncertainty_rotation");
    if (plan.target_uncertainty > 0 || plan.target_uncertainty_rotation > 0) {
      // Only the joint method reports an uncertainty; the paper's median has none to reach.
      if (plan.method != "joint") {
        throw imagenets::BlockError("property 'target_uncertainty': an uncertainty target needs the joint method "
                                    "(the paper method reports no covariance), method is '" + plan.method + "'");
      }
      const int max_poses = ctx.property<int>("max_poses");
      if (max_poses < plan.samples) {
        throw imagenets::BlockError("property 'max_poses': " + std::to_string(max_poses) + " is below the " +
                                    std::to_string(plan.samples) + " poses the plan takes anyway");
      }
      plan.max_samples = max_poses;
    }
    addPoses(ctx, model, plan);
  }

  static void addPoses(imagenets::Context& ctx, const RobotModel& model,
                       imagenets_calibration_msgs::CalibrationPlan& plan) {
    const auto& d = model.description();
    const double away = ctx.property<double>("reapproach_deg") * M_PI / 180.0;
    // calibrationPoses(n)'s first k poses are those of calibrationPoses(k): the poses added for a
    // target are the ones a larger plan would have taken next.
    for (const auto& pose : calibrationPoses(model, plan.max_samples, plan.method)) {
      sensor_msgs::JointState arm, head, approach;
      arm.name = approach.name = d.arm.names();
      head.name = d.head.names();
      arm.position = approach.position = pose.arm;
      head.position = pose.head;
      // The paper's procedure comes to the calibration pose anew every loop (the first too).
      if (plan.method == "paper" && approach.position.size() > 3) approach.position[3] -= away;
      plan.arm.push_back(arm);
      plan.head.push_back(head);
      plan.arm_approach.push_back(approach);
    }
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::CalibrationPlan, "imagenets/CalibrationPlan", "calibration",
                         "FRIEND calibration plan: method, sample count, the pose of each sample or a replay file");
