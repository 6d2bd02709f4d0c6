#include <gtest/gtest.h>
#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <std_msgs/Bool.h>

#include "imagenets/blocks/block_harness.h"

using imagenets::blocks::BlockHarness;

namespace {

// A successful result whose fixed point has 1 mm and 0.1 deg standard deviation per axis:
// 3 sigma = 3 sqrt(3) x that = 5.2 mm / 0.52 deg.
boost::shared_ptr<imagenets_calibration_msgs::CalibrationResult> result(bool success = true) {
  auto r = boost::make_shared<imagenets_calibration_msgs::CalibrationResult>();
  r->success = success;
  r->method = "joint";
  r->fixed_point.transform.rotation.w = 1;
  r->marker_offset.orientation.w = 1;
  for (int i = 0; i < 3; ++i) r->fixed_point_covariance[i * 7] = 1e-6;
  for (int i = 3; i < 6; ++i) r->fixed_point_covariance[i * 7] = std::pow(0.1 * M_PI / 180, 2);
  return r;
}

bool met(double target, double target_rotation, const boost::shared_ptr<imagenets_calibration_msgs::CalibrationResult>& r = result()) {
  auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
  plan->method = "joint";
  plan->target_uncertainty = target;
  plan->target_uncertainty_rotation = target_rotation;
  BlockHarness h("imagenets/CalibrationTargetMet");
  h.input("plan", plan).input("result", r);
  h.run();
  return h.output<std_msgs::Bool>("met")->data;
}

}  // namespace

TEST(CalibrationTargetMet, ComparesTheThreeSigmaBoundsWithThePlansTargets) {
  const double deg = M_PI / 180;
  EXPECT_TRUE(met(0.0053, 0));
  EXPECT_FALSE(met(0.0051, 0));
  EXPECT_TRUE(met(0, 0.53 * deg));
  EXPECT_FALSE(met(0, 0.51 * deg));
  EXPECT_FALSE(met(0.0053, 0.51 * deg));  // both must hold
  EXPECT_TRUE(met(0.0053, 0.53 * deg));
  EXPECT_FALSE(met(0, 0));                // no target: nothing to meet
  EXPECT_FALSE(met(0.1, 0, result(false)));  // a failed calibration meets nothing
  auto none = result();
  none->fixed_point_covariance.fill(0);      // no covariance (paper method)
  EXPECT_FALSE(met(0.1, 0, none));
}
