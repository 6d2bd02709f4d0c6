#include "friend_hw_sim/joint_group_server.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace friend_hw_sim {

JointGroupServer::JointGroupServer(ros::NodeHandle nh, const std::string& action_name, const robot_description::KinematicChain& chain,
                                   const std::vector<double>& start, std::string fault_param, unsigned seed)
    : nh_(nh), action_name_(nh.resolveName(action_name)), chain_(chain), fault_param_(std::move(fault_param)), q_(start), qd_(start.size(), 0.0), rng_(seed) {
  if (start.size() != chain.joints.size()) throw std::invalid_argument("JointGroupServer: start size mismatch");
  server_ = std::make_unique<Server>(
      nh_, action_name, [this](GoalHandle gh) { onGoal(gh); }, [this](GoalHandle gh) { onCancel(gh); }, false);
  server_->start();
}

JointGroupServer::~JointGroupServer() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (active_) goal_.setAborted(resultLocked("simulator shutting down"), "simulator shutting down");
  active_ = false;
}

friend_msgs::MoveJointsResult JointGroupServer::resultLocked(const std::string& message) const {
  friend_msgs::MoveJointsResult r;
  r.joint_names = chain_.names();
  r.positions = q_;
  r.message = message;
  return r;
}

void JointGroupServer::onGoal(GoalHandle gh) {
  const auto goal = gh.getGoal();
  std::lock_guard<std::mutex> lock(mutex_);
  // Targets in the server's joint order; unnamed joints keep their position.
  std::vector<double> target = q_;
  std::string reason;
  if (goal->joint_names.empty()) {
    if (goal->positions.size() != q_.size()) {
      reason = "expected " + std::to_string(q_.size()) + " positions (joints " + [&] {
        std::string s;
        for (const auto& n : chain_.names()) s += (s.empty() ? "" : ", ") + n;
        return s;
      }() + "), got " + std::to_string(goal->positions.size());
    } else {
      target = goal->positions;
    }
  } else if (goal->joint_names.size() != goal->positions.size()) {
    reason = "joint_names has " + std::to_string(goal->joint_names.size()) + " entries but positions has " +
             std::to_string(goal->positions.size());
  } else {
    const auto names = chain_.names();
    for (size_t i = 0; i < goal->joint_names.size() && reason.empty(); ++i) {
      const auto it = std::find(names.begin(), names.end(), goal->joint_names[i]);
      if (it == names.end()) reason = "unknown joint '" + goal->joint_names[i] + "'";
      else target[it - names.begin()] = goal->positions[i];
    }
  }
  if (reason.empty()) reason = chain_.limitViolation(target);
  const double speed = goal->speed_scale == 0 ? 1.0 : goal->speed_scale;
  if (reason.empty() && !(speed > 0 && speed <= 1)) {
    reason = "speed_scale " + std::to_string(goal->speed_scale) + " is outside (0, 1]";
  }
  if (!reason.empty()) {
    ROS_WARN("%s: rejected goal: %s", action_name_.c_str(), reason.c_str());
    gh.setRejected(resultLocked("rejected: " + reason), reason);
    return;
  }
  if (active_) {
    goal_.setCanceled(resultLocked("preempted by a new goal"), "preempted by a new goal");
    active_ = false;
  }
  std::vector<double> vmax;
  for (const auto& j : chain_.joints) vmax.push_back(j.max_velocity);
  trajectory_ = JointTrajectory(q_, target, vmax, speed);
  t_ = 0;
  double p_fault = 0;
  nh_.getParamCached(fault_param_, p_fault);
  abort_at_ = 2.0;
  if (p_fault > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < p_fault) {
    abort_at_ = std::uniform_real_distribution<double>(0.2, 0.8)(rng_);
  }
  goal_ = gh;
  active_ = true;
  gh.setAccepted("moving");
}

void JointGroupServer::onCancel(GoalHandle gh) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (active_ && gh == goal_) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    goal_.setCanceled(resultLocked("canceled: stopped where the joints were"), "canceled");
    active_ = false;
  }
}

void JointGroupServer::step(double sim_dt) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!active_) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    return;
  }
  t_ += sim_dt;
  const std::vector<double> previous = q_;
  q_ = trajectory_.positionAt(t_);
  for (size_t i = 0; i < q_.size(); ++i) qd_[i] = sim_dt > 0 ? (q_[i] - previous[i]) / sim_dt : 0.0;
  const double progress = trajectory_.progressAt(t_);
  if (progress >= abort_at_) {
    std::ostringstream why;
    why << "simulated fault: the controller aborted the motion at " << static_cast<int>(progress * 100)
        << "% of the trajectory";
    std::fill(qd_.begin(), qd_.end(), 0.0);
    goal_.setAborted(resultLocked(why.str()), why.str());
    active_ = false;
    return;
  }
  if (progress >= 1.0) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    goal_.setSucceeded(resultLocked("reached"), "reached");
    active_ = false;
    return;
  }
  friend_msgs::MoveJointsFeedback fb;
  fb.joint_names = chain_.names();
  fb.positions = q_;
  fb.progress = progress;
  goal_.publishFeedback(fb);
}

std::vector<double> JointGroupServer::positions() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return q_;
}
std::vector<double> JointGroupServer::velocities() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return qd_;
}
bool JointGroupServer::moving() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return active_;
}

}  // namespace friend_hw_sim
