// Which estimated parameters the calibration poses determine (observability.h): the judgement on
// a Jacobian built by hand, and predictObservability on plans of poses at the nominal robot.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "imagenets_calibration/bundle_adjustment.h"
#include "imagenets_calibration/observability.h"

namespace imagenets_calibration {
namespace {

constexpr double kDeg = M_PI / 180.0;
// Point noise of the simulator's detections at the calibration distance (docs/calibration-method.md).
constexpr double kNoisePx = 0.05;

bool names(const Observability& o, const std::string& name) {
  return std::find(o.unobservable.begin(), o.unobservable.end(), name) != o.unobservable.end();
}

void print(const char* what, const Observability& o) {
  std::printf("%s: %s\n", what, o.summary().c_str());
  for (const auto& p : o.parameters) {
    std::printf("  %-22s prior %10.3g posterior %10.3g ratio %6.3f%s\n", p.name.c_str(), p.prior_std, p.posterior_std,
                p.posterior_std / p.prior_std, p.observable() ? "" : "  NOT OBSERVABLE");
  }
}

TEST(Observability, APosteriorNotClearlyBelowThePriorIsNamedAndAnUnseenDirectionMakesTheConditionInfinite) {
  // Three parameters: a is measured well, b barely (its prior dominates), c not at all (only its
  // prior row); the last three rows are the priors (std 1).
  Eigen::MatrixXd j(5, 3);
  j << 100, 0, 0,  //
      0, 0.5, 0,   //
      1, 0, 0,     //
      0, 1, 0,     //
      0, 0, 1;
  const Observability o = analyseObservability(j, 2, {"a", "b", "c"}, {1, 1, 1});
  ASSERT_EQ(o.parameters.size(), 3u);
  EXPECT_NEAR(o.parameters[0].posterior_std, 1 / std::sqrt(10001.0), 1e-12);
  EXPECT_NEAR(o.parameters[1].posterior_std, 1 / std::sqrt(1.25), 1e-12);
  EXPECT_EQ(o.unobservable, (std::vector<std::string>{"b", "c"}));
  EXPECT_TRUE(std::isinf(o.condition_number));
  EXPECT_NE(o.summary().find("not observable from these poses (posterior std > 0.5 x prior): b, c"), std::string::npos)
      << o.summary();
  // Measured well enough: all observable, a finite condition number (singular values 100 and 5).
  j(1, 1) = 5;
  j(2, 2) = 0;
  Eigen::MatrixXd data(3, 3);
  data << 100, 0, 0, 0, 5, 0, 0, 0, 4;
  const Observability all = analyseObservability(data, 3, {"a", "b", "c"}, {1, 1, 1});
  EXPECT_TRUE(all.unobservable.empty());
  EXPECT_NEAR(all.condition_number, 25.0, 1e-9);
  EXPECT_NE(all.summary().find("every estimated parameter observable"), std::string::npos);
  // A variance factor above 1 widens the posterior (and can make a parameter unobservable).
  const Observability noisy = analyseObservability(data, 3, {"a", "b", "c"}, {1, 1, 1}, 16.0);
  EXPECT_NEAR(noisy.parameters[2].posterior_std, 1.0, 1e-12);
  EXPECT_EQ(noisy.unobservable, (std::vector<std::string>{"b", "c"}));
  // A parameter without any row at all is undetermined: infinite posterior.
  Eigen::MatrixXd none = Eigen::MatrixXd::Zero(2, 2);
  none(0, 0) = 1;
  EXPECT_TRUE(std::isinf(analyseObservability(none, 1, {"a", "b"}, {1, 1}).parameters[1].posterior_std));
  EXPECT_THROW(analyseObservability(none, 1, {"a"}, {1, 1}), std::invalid_argument);
}

struct PlanObservability : ::testing::Test {
  RobotModel model{robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath())};
  CameraModels cameras = *cameraModelsOf(model.description(), nullptr);

  // `count` poses that turn only arm joint `joint` (0-based) about the calibration pose, the head
  // following the marker.
  std::vector<CalibrationPose> oneJointPlan(size_t joint, int count) const {
    const auto& d = model.description();
    std::vector<CalibrationPose> poses;
    for (int k = 0; k < count; ++k) {
      CalibrationPose p;
      p.arm = d.arm_calibration_pose;
      p.arm[joint] += (k - (count - 1) / 2.0) * 8 * kDeg;
      const auto look = model.lookAt(model.marker(p.arm).translation(), {d.head_calibration_pose[0], d.head_calibration_pose[1]});
      p.head = {look[0], look[1]};
      poses.push_back(p);
    }
    return poses;
  }
};

TEST_F(PlanObservability, APlanThatTurnsOnlyTheWristLeavesNamedParametersUnobservable) {
  const Observability o = predictObservability(model, cameras, oneJointPlan(6, 10), kNoisePx);
  print("only arm_joint_7 turned, 10 poses", o);
  ASSERT_TRUE(o.computed());
  EXPECT_FALSE(o.unobservable.empty());
  // Only the last joint turns: the offsets of the joints before it stay one rigid chain, which
  // the poses cannot take apart.
  EXPECT_TRUE(names(o, "arm_joint_3 offset")) << o.summary();
  EXPECT_NE(o.summary().find("not observable from these poses"), std::string::npos);
}

TEST_F(PlanObservability, TheDefaultPlanDeterminesEveryEstimatedParameter) {
  const Observability o = predictObservability(model, cameras, calibrationPoses(model, 10, "joint"), kNoisePx);
  print("default plan (joint, 5 loops x 2 poses)", o);
  ASSERT_TRUE(o.computed());
  EXPECT_TRUE(o.unobservable.empty()) << o.summary();
  EXPECT_TRUE(std::isfinite(o.condition_number));
}

TEST_F(PlanObservability, OneLoopOfTwoPosesLeavesTheMarkersRotationAndTheFixedPointUndetermined) {
  const Observability o = predictObservability(model, cameras, calibrationPoses(model, 2, "joint"), kNoisePx);
  print("one loop (2 poses)", o);
  ASSERT_TRUE(o.computed());
  EXPECT_TRUE(std::any_of(o.unobservable.begin(), o.unobservable.end(),
                          [](const std::string& n) { return n.rfind("marker offset r", 0) == 0; }))
      << o.summary();
  EXPECT_TRUE(std::any_of(o.unobservable.begin(), o.unobservable.end(),
                          [](const std::string& n) { return n.rfind("fixed point", 0) == 0; }))
      << o.summary();
}

}  // namespace
}  // namespace imagenets_calibration
