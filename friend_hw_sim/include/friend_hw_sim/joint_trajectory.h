// A smooth point-to-point joint trajectory that respects per-joint velocity limits: all joints
// start and stop together (quintic time scaling, zero velocity and acceleration at both ends).
#pragma once

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

}  // namespace friend_hw_sim
