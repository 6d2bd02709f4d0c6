// Joint trajectories the simulated controllers follow.
//
// JointTrajectory: a smooth point-to-point motion that respects per-joint velocity limits: all
// joints start and stop together (quintic time scaling, zero velocity and acceleration at both
// ends). The MoveJoints servers move this way.
//
// SplineTrajectory: what ros_control's joint_trajectory_controller makes of a
// trajectory_msgs/JointTrajectory: one polynomial segment per waypoint from the previous state,
// quintic where the waypoint gives velocities and accelerations, cubic where it gives velocities,
// linear where it gives positions only; the first segment starts at the joints' current state.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace friend_hw_sim {

class JointTrajectory {
 public:
  JointTrajectory() = default;
  // max_velocity in rad/s per joint; speed_scale in (0, 1].
  JointTrajectory(std::vector<double> start, std::vector<double> goal, const std::vector<double>& max_velocity,
                  double speed_scale);

  double duration() const { return duration_; }  // s
  std::vector<double> positionAt(double t) const;
  double progressAt(double t) const;  // 0..1 of the duration
  const std::vector<double>& goal() const { return goal_; }

  // Peak speed of the quintic is 15/8 of the mean speed.
  static constexpr double kPeakToMean = 1.875;

 private:
  std::vector<double> start_, goal_;
  double duration_ = 0;
};

// One waypoint: time from the trajectory's start (s), positions, and optionally velocities and
// accelerations (empty: not given), all in the controller's joint order.
struct Waypoint {
  double time = 0;
  std::vector<double> positions, velocities, accelerations;
};

class SplineTrajectory {
 public:
  SplineTrajectory() = default;
  // From the state (q0, v0, a0) at t = 0 through the waypoints, whose times must increase
  // strictly from above 0 and whose sizes must match q0 (std::invalid_argument otherwise).
  SplineTrajectory(const std::vector<double>& q0, const std::vector<double>& v0, const std::vector<double>& a0,
                   const std::vector<Waypoint>& waypoints);

  double duration() const { return segments_.empty() ? 0.0 : segments_.back().end; }  // s
  size_t size() const { return goal_.size(); }
  // Positions and velocities at t (before 0: the start, after the end: the last waypoint at rest).
  void sample(double t, std::vector<double>* q, std::vector<double>* qd = nullptr) const;
  const std::vector<double>& goal() const { return goal_; }
  // The largest |velocity| of joint j over the whole trajectory and when it occurs (sampled
  // densely, plus the segment ends).
  double peakVelocity(size_t j, double* at = nullptr) const;

 private:
  struct Segment {
    double start = 0, end = 0;
    std::vector<std::array<double, 6>> coefficients;  // per joint, in powers of (t - start)
  };
  std::vector<Segment> segments_;
  std::vector<double> start_, goal_;
};

}  // namespace friend_hw_sim
