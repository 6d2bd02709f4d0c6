// The maths and the words of the FollowJointTrajectory block (hardware/follow_joint_trajectory.cpp),
// without ROS communication, so that its tests need no controller.
#pragma once

#include <string>
#include <vector>

#include <control_msgs/FollowJointTrajectoryAction.h>
#include <sensor_msgs/JointState.h>

namespace imagenets {
namespace blocks {
namespace hardware {

// A motion from rest to rest: the single waypoint below, which joint_trajectory_controller
// interpolates from the joints' state at rest as a quintic (zero velocity and acceleration at
// both ends), every joint starting and stopping together.
struct PointToPointMotion {
  std::vector<std::string> joints;
  std::vector<double> start, target;  // rad (or m), in the order of joints
  double duration = 0;                // s
  // Where joint j should be t s after the start.
  double position(size_t j, double t) const;
};

// The quintic's peak speed is 15/8 of its mean: the fastest joint peaks at max_velocity with
// duration = 1.875 max|target - start| / max_velocity, at least min_duration.
PointToPointMotion pointToPoint(const std::vector<std::string>& joints, const std::vector<double>& start,
                                const std::vector<double>& target, double max_velocity, double min_duration);

// Tolerances for every joint, as control_msgs/JointTolerance has them: > 0 that value, 0 the
// controller's default, < 0 none.
struct TrajectoryTolerances {
  double path = 0;       // rad, while moving
  double goal = 0;       // rad, at the end
  double goal_time = 0;  // s after the end by which the goal tolerance must hold (0: the controller's)
};

// One waypoint at the target at `duration` with zero velocities and accelerations; the header's
// stamp zero (the controller starts on receipt); path and goal tolerance for every joint.
control_msgs::FollowJointTrajectoryGoal trajectoryGoal(const PointToPointMotion& motion,
                                                       const TrajectoryTolerances& tolerances);

// "GOAL_TOLERANCE_VIOLATED (-5)".
std::string trajectoryErrorName(int code);

// Why a goal did not succeed, for a BlockError: the action, the final state and the controller's
// error code and text, and what the joints measured afterwards (`measured`, may be null) say:
// which joint was outside which tolerance, by how much. `elapsed`: seconds from sending the goal
// to its end.
std::string trajectoryFailure(const std::string& action, const std::string& state, int error_code,
                              const std::string& error_string, const PointToPointMotion& motion,
                              const TrajectoryTolerances& tolerances, double elapsed,
                              const sensor_msgs::JointState* measured);

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
