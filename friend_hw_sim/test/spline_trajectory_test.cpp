// The simulated trajectory controllers' interpolation (as joint_trajectory_controller's).
#include <cmath>

#include <gtest/gtest.h>

#include "friend_hw_sim/joint_trajectory.h"

using friend_hw_sim::JointTrajectory;
using friend_hw_sim::SplineTrajectory;
using friend_hw_sim::Waypoint;

namespace {
Waypoint point(double t, std::vector<double> q, std::vector<double> v = {}, std::vector<double> a = {}) {
  return Waypoint{t, std::move(q), std::move(v), std::move(a)};
}
}  // namespace

TEST(SplineTrajectory, RestToRestWaypointIsTheQuinticOfThePointToPointMotion) {
  const std::vector<double> start{0.1, -0.4}, goal{0.9, 0.2};
  const JointTrajectory p2p(start, goal, {0.5, 0.5}, 1.0);
  const SplineTrajectory s(start, {0, 0}, {0, 0}, {point(p2p.duration(), goal, {0, 0}, {0, 0})});
  EXPECT_DOUBLE_EQ(s.duration(), p2p.duration());
  std::vector<double> q, qd;
  for (double u : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
    s.sample(u * s.duration(), &q, &qd);
    const auto expected = p2p.positionAt(u * s.duration());
    EXPECT_NEAR(q[0], expected[0], 1e-12) << u;
    EXPECT_NEAR(q[1], expected[1], 1e-12) << u;
  }
  EXPECT_EQ(q, goal);  // exactly at the end
  EXPECT_NEAR(s.peakVelocity(0), 0.5, 1e-4);  // 1.875 x mean speed: the joint's limit here
}

TEST(SplineTrajectory, PositionsOnlyAreLinearAndVelocitiesCubic) {
  const SplineTrajectory linear({0.0}, {0.0}, {0.0}, {point(1.0, {1.0}), point(3.0, {0.0})});
  std::vector<double> q, qd;
  linear.sample(0.25, &q, &qd);
  EXPECT_NEAR(q[0], 0.25, 1e-12);
  EXPECT_NEAR(qd[0], 1.0, 1e-12);
  linear.sample(2.0, &q, &qd);
  EXPECT_NEAR(q[0], 0.5, 1e-12);
  EXPECT_NEAR(qd[0], -0.5, 1e-12);

  // Cubic through a waypoint with a velocity: position and velocity continuous there.
  const SplineTrajectory cubic({0.0}, {0.2}, {0.0}, {point(1.0, {1.0}, {0.5}), point(2.0, {1.2}, {0.0})});
  cubic.sample(1e-9, &q, &qd);
  EXPECT_NEAR(qd[0], 0.2, 1e-6);  // starts with the joint's velocity
  std::vector<double> q_before, qd_before, q_after, qd_after;
  cubic.sample(1.0 - 1e-9, &q_before, &qd_before);
  cubic.sample(1.0 + 1e-9, &q_after, &qd_after);
  EXPECT_NEAR(q_before[0], 1.0, 1e-6);
  EXPECT_NEAR(q_after[0], 1.0, 1e-6);
  EXPECT_NEAR(qd_before[0], 0.5, 1e-6);
  EXPECT_NEAR(qd_after[0], 0.5, 1e-6);
  cubic.sample(5.0, &q, &qd);
  EXPECT_EQ(q[0], 1.2);
  EXPECT_EQ(qd[0], 0.0);
}

TEST(SplineTrajectory, QuinticMatchesTheWaypointsAccelerations) {
  const SplineTrajectory s({0.0}, {0.0}, {0.0}, {point(1.0, {0.5}, {0.3}, {-0.2}), point(2.0, {1.0}, {0.0}, {0.0})});
  std::vector<double> a, b, c;
  const double h = 1e-5;
  s.sample(1.0 - 2 * h, &a);
  s.sample(1.0 - h, &b);
  s.sample(1.0 - 1e-12, &c);
  EXPECT_NEAR(c[0], 0.5, 1e-9);
  EXPECT_NEAR((c[0] - b[0]) / h, 0.3, 1e-4);
  EXPECT_NEAR((c[0] - 2 * b[0] + a[0]) / (h * h), -0.2, 1e-2);
}

TEST(SplineTrajectory, RejectsWaypointsThatDoNotMoveForwardInTime) {
  EXPECT_THROW(SplineTrajectory({0.0}, {0.0}, {0.0}, {point(0.0, {1.0})}), std::invalid_argument);
  EXPECT_THROW(SplineTrajectory({0.0}, {0.0}, {0.0}, {point(1.0, {1.0}), point(1.0, {2.0})}), std::invalid_argument);
  EXPECT_THROW(SplineTrajectory({0.0}, {0.0}, {0.0}, {point(1.0, {1.0, 2.0})}), std::invalid_argument);
}
