#include "follow_joint_trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace imagenets {
namespace blocks {
namespace hardware {
namespace {

using control_msgs::FollowJointTrajectoryResult;

constexpr double kPeakToMean = 1.875;  // of the quintic with zero velocity and acceleration at both ends

std::string number(double v, const char* fmt = "%.4f") {
  char b[64];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

// The tolerance in words: "0.0100 rad (property goal_tolerance)".
std::string tolerance(double value, const std::string& property) {
  if (value > 0) return number(value) + " rad (property " + property + ")";
  if (value == 0) return "the controller's default (property " + property + " 0)";
  return "none (property " + property + " < 0)";
}

}  // namespace

double PointToPointMotion::position(size_t j, double t) const {
  const double u = duration > 0 ? std::min(1.0, std::max(0.0, t / duration)) : 1.0;
  const double s = u * u * u * (10 - 15 * u + 6 * u * u);
  return start.at(j) + s * (target.at(j) - start.at(j));
}

PointToPointMotion pointToPoint(const std::vector<std::string>& joints, const std::vector<double>& start,
                                const std::vector<double>& target, double max_velocity, double min_duration) {
  if (joints.size() != start.size() || joints.size() != target.size()) {
    throw std::invalid_argument("pointToPoint: joints, start and target differ in size");
  }
  if (!(max_velocity > 0)) throw std::invalid_argument("pointToPoint: max_velocity must be positive");
  PointToPointMotion m{joints, start, target, std::max(0.0, min_duration)};
  for (size_t j = 0; j < joints.size(); ++j) {
    m.duration = std::max(m.duration, kPeakToMean * std::abs(target[j] - start[j]) / max_velocity);
  }
  return m;
}

control_msgs::FollowJointTrajectoryGoal trajectoryGoal(const PointToPointMotion& motion,
                                                       const TrajectoryTolerances& tolerances) {
  control_msgs::FollowJointTrajectoryGoal goal;
  goal.trajectory.joint_names = motion.joints;  // header.stamp zero: start on receipt
  trajectory_msgs::JointTrajectoryPoint point;
  point.positions = motion.target;
  point.velocities.assign(motion.joints.size(), 0.0);
  point.accelerations.assign(motion.joints.size(), 0.0);
  point.time_from_start = ros::Duration(motion.duration);
  goal.trajectory.points.push_back(point);
  for (const auto& name : motion.joints) {
    control_msgs::JointTolerance path, at_goal;
    path.name = at_goal.name = name;
    path.position = tolerances.path;
    at_goal.position = tolerances.goal;
    goal.path_tolerance.push_back(path);
    goal.goal_tolerance.push_back(at_goal);
  }
  goal.goal_time_tolerance = ros::Duration(std::max(0.0, tolerances.goal_time));
  return goal;
}

std::string trajectoryErrorName(int code) {
  const char* name = "unknown error code";
  switch (code) {
    case FollowJointTrajectoryResult::SUCCESSFUL: name = "SUCCESSFUL"; break;
    case FollowJointTrajectoryResult::INVALID_GOAL: name = "INVALID_GOAL"; break;
    case FollowJointTrajectoryResult::INVALID_JOINTS: name = "INVALID_JOINTS"; break;
    case FollowJointTrajectoryResult::OLD_HEADER_TIMESTAMP: name = "OLD_HEADER_TIMESTAMP"; break;
    case FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED: name = "PATH_TOLERANCE_VIOLATED"; break;
    case FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED: name = "GOAL_TOLERANCE_VIOLATED"; break;
    default: break;
  }
  return std::string(name) + " (" + std::to_string(code) + ")";
}

std::string trajectoryFailure(const std::string& action, const std::string& state, int error_code,
                              const std::string& error_string, const PointToPointMotion& motion,
                              const TrajectoryTolerances& tolerances, double elapsed,
                              const sensor_msgs::JointState* measured) {
  std::string why = "'" + action + "' " + state;
  if (state == "PREEMPTED") {
    why += " the goal after " + number(elapsed, "%.2f") + " s of its " + number(motion.duration, "%.2f") +
           " s: another goal reached the controller, or someone canceled this one";
  } else {
    why += " the goal: " + trajectoryErrorName(error_code);
  }
  if (!error_string.empty()) why += ": " + error_string;

  // What the joints say, measured after the end.
  auto measuredAt = [&](size_t j, double* q) {
    if (!measured) return false;
    for (size_t i = 0; i < measured->name.size() && i < measured->position.size(); ++i) {
      if (measured->name[i] == motion.joints[j]) {
        *q = measured->position[i];
        return true;
      }
    }
    return false;
  };
  if (error_code == FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED ||
      error_code == FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED) {
    const bool at_goal = error_code == FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED;
    const double t = at_goal ? motion.duration : std::min(elapsed, motion.duration);
    int worst = -1;
    double worst_error = -1, worst_q = 0, worst_ref = 0;
    for (size_t j = 0; j < motion.joints.size(); ++j) {
      double q = 0;
      if (!measuredAt(j, &q)) continue;
      const double ref = motion.position(j, t);
      if (std::abs(q - ref) > worst_error) {
        worst = static_cast<int>(j);
        worst_error = std::abs(q - ref);
        worst_q = q;
        worst_ref = ref;
      }
    }
    if (worst >= 0) {
      why += "; measured afterwards, joint '" + motion.joints[worst] + "' is at " + number(worst_q) + " rad, " +
             number(worst_error) + " rad from " +
             (at_goal ? "its goal " + number(worst_ref) + " rad (goal tolerance " +
                            tolerance(tolerances.goal, "goal_tolerance") + ", goal_time_tolerance " +
                            (tolerances.goal_time > 0 ? number(tolerances.goal_time, "%.2f") + " s" : "the controller's") +
                            ")"
                      : "where the trajectory had it at t = " + number(t, "%.2f") + " s, " + number(worst_ref) +
                            " rad (path tolerance " + tolerance(tolerances.path, "path_tolerance") + ")");
    }
  } else if (error_code == FollowJointTrajectoryResult::INVALID_JOINTS) {
    std::string names;
    for (const auto& n : motion.joints) names += (names.empty() ? "" : ", ") + n;
    why += "; the goal named " + names + " (the input's joints, or property joints: name every joint the controller has)";
  } else if (error_code == FollowJointTrajectoryResult::INVALID_GOAL) {
    why += "; the goal moved to the input's positions in " + number(motion.duration, "%.2f") +
           " s (property max_velocity): check the joint limits and the speed";
  } else if (error_code == FollowJointTrajectoryResult::OLD_HEADER_TIMESTAMP) {
    why += "; the controller's clock differs from this process's (use_sim_time?)";
  }
  return why;
}

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
