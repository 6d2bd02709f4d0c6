#include "friend_hw_sim/joint_trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace friend_hw_sim {

JointTrajectory::JointTrajectory(std::vector<double> start, std::vector<double> goal,
                                 const std::vector<double>& max_velocity, double speed_scale)
    : start_(std::move(start)), goal_(std::move(goal)) {
  if (start_.size() != goal_.size() || goal_.size() != max_velocity.size()) {
    throw std::invalid_argument("JointTrajectory: start, goal and velocity sizes differ");
  }
  if (!(speed_scale > 0 && speed_scale <= 1)) throw std::invalid_argument("JointTrajectory: speed_scale must be in (0, 1]");
  for (size_t i = 0; i < goal_.size(); ++i) {
    duration_ = std::max(duration_, kPeakToMean * std::abs(goal_[i] - start_[i]) / (max_velocity[i] * speed_scale));
  }
}

double JointTrajectory::progressAt(double t) const {
  if (duration_ <= 0) return 1.0;
  return std::min(1.0, std::max(0.0, t / duration_));
}

std::vector<double> JointTrajectory::positionAt(double t) const {
  const double u = progressAt(t);
  const double s = u * u * u * (10 - 15 * u + 6 * u * u);  // quintic: s(0)=0, s(1)=1, s'=s''=0 at ends
  std::vector<double> q(goal_.size());
  for (size_t i = 0; i < q.size(); ++i) q[i] = start_[i] + s * (goal_[i] - start_[i]);
  if (u >= 1.0) q = goal_;
  return q;
}

}  // namespace friend_hw_sim
