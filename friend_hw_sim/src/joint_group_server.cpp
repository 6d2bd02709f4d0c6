#include "friend_hw_sim/joint_group_server.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace friend_hw_sim {
namespace {

using control_msgs::FollowJointTrajectoryResult;

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c, d);
  return buffer;
}

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

JointGroupServer::JointGroupServer(ros::NodeHandle nh, const JointGroupConfig& config,
                                   const robot_description::KinematicChain& chain, const std::vector<double>& start)
    : nh_(nh),
      config_(config),
      move_action_(config.move_action.empty() ? "" : nh.resolveName(config.move_action)),
      chain_(chain),
      q_(start),
      qd_(start.size(), 0.0),
      rng_(config.seed) {
  if (start.size() != chain.joints.size()) throw std::invalid_argument("JointGroupServer: start size mismatch");
  if (!config.move_action.empty()) {
    move_server_ = std::make_unique<MoveServer>(
        nh_, config.move_action, [this](MoveServer::GoalHandle gh) { onMoveGoal(gh); },
        [this](MoveServer::GoalHandle gh) { onMoveCancel(gh); }, false);
    move_server_->start();
  }
  if (!config.trajectory_action.empty()) {
    trajectory_action_ = nh.resolveName(config.trajectory_action);
    trajectory_server_ = std::make_unique<TrajectoryServer>(
        nh_, config.trajectory_action, [this](TrajectoryServer::GoalHandle gh) { onTrajectoryGoal(gh); },
        [this](TrajectoryServer::GoalHandle gh) { onTrajectoryCancel(gh); }, false);
    trajectory_server_->start();
  }
}

JointGroupServer::~JointGroupServer() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (mode_ == Mode::move) move_goal_.setAborted(moveResultLocked("simulator shutting down"), "simulator shutting down");
  if (mode_ == Mode::trajectory) {
    FollowJointTrajectoryResult r;
    r.error_code = FollowJointTrajectoryResult::INVALID_GOAL;
    r.error_string = "simulator shutting down";
    trajectory_goal_.setAborted(r, r.error_string);
  }
  mode_ = Mode::idle;
}

// Read when a goal arrives, from the master (not its cache: a test's or a user's change holds for
// the very next goal).
double JointGroupServer::param(const std::string& name, double fallback) const {
  double value = fallback;
  nh_.getParam(name, value);
  return value;
}

friend_msgs::MoveJointsResult JointGroupServer::moveResultLocked(const std::string& message) const {
  friend_msgs::MoveJointsResult r;
  r.joint_names = chain_.names();
  r.positions = q_;
  r.message = message;
  return r;
}

void JointGroupServer::preemptLocked(const std::string& why) {
  if (mode_ == Mode::move) move_goal_.setCanceled(moveResultLocked(why), why);
  if (mode_ == Mode::trajectory) {
    FollowJointTrajectoryResult r;
    r.error_string = why;
    trajectory_goal_.setCanceled(r, why);
  }
  mode_ = Mode::idle;
  std::fill(qd_.begin(), qd_.end(), 0.0);
}

// ---- friend_msgs/MoveJoints ----

void JointGroupServer::onMoveGoal(MoveServer::GoalHandle gh) {
  const auto goal = gh.getGoal();
  std::lock_guard<std::mutex> lock(mutex_);
  // Targets in the server's joint order; unnamed joints keep their position.
  std::vector<double> target = q_;
  std::string reason;
  if (goal->joint_names.empty()) {
    if (goal->positions.size() != q_.size()) {
      reason = "expected " + std::to_string(q_.size()) + " positions (joints " + joinNames(chain_.names()) + "), got " +
               std::to_string(goal->positions.size());
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
    ROS_WARN("%s: rejected goal: %s", move_action_.c_str(), reason.c_str());
    gh.setRejected(moveResultLocked("rejected: " + reason), reason);
    return;
  }
  preemptLocked("preempted by a new goal");
  std::vector<double> vmax;
  for (const auto& j : chain_.joints) vmax.push_back(j.max_velocity);
  move_trajectory_ = JointTrajectory(q_, target, vmax, speed);
  t_ = 0;
  const double p_fault = param(config_.abort_probability_param, 0.0);
  abort_at_ = 2.0;
  if (p_fault > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < p_fault) {
    abort_at_ = std::uniform_real_distribution<double>(0.2, 0.8)(rng_);
  }
  move_goal_ = gh;
  mode_ = Mode::move;
  gh.setAccepted("moving");
}

void JointGroupServer::onMoveCancel(MoveServer::GoalHandle gh) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (mode_ == Mode::move && gh == move_goal_) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    move_goal_.setCanceled(moveResultLocked("canceled: stopped where the joints were"), "canceled");
    mode_ = Mode::idle;
  }
}

// ---- control_msgs/FollowJointTrajectory ----

void JointGroupServer::onTrajectoryGoal(TrajectoryServer::GoalHandle gh) {
  const auto goal = gh.getGoal();
  std::lock_guard<std::mutex> lock(mutex_);
  FollowJointTrajectoryResult result;
  auto reject = [&](int code, const std::string& why) {
    ROS_WARN("%s: rejected goal: %s", trajectory_action_.c_str(), why.c_str());
    result.error_code = code;
    result.error_string = why;
    gh.setRejected(result, why);
  };
  if (goal->trajectory.points.empty()) {  // as joint_trajectory_controller: stop where the joints are
    preemptLocked("stopped by an empty trajectory");
    gh.setAccepted("stopping");
    result.error_string = "stopped";
    gh.setSucceeded(result, "stopped");
    return;
  }
  // The goal's joints must be the controller's (any order); with allow_partial_joints_goal a
  // subset, the others holding their position.
  const auto names = chain_.names();
  std::vector<int> index;
  std::vector<bool> named(names.size(), false);
  std::string unknown, twice, missing;
  for (const auto& n : goal->trajectory.joint_names) {
    const auto it = std::find(names.begin(), names.end(), n);
    const int i = it == names.end() ? -1 : static_cast<int>(it - names.begin());
    if (i < 0) unknown += (unknown.empty() ? "'" : ", '") + n + "'";
    else if (named[i]) twice += (twice.empty() ? "'" : ", '") + n + "'";
    else named[i] = true;
    index.push_back(i);
  }
  bool partial = false;
  nh_.getParam(config_.controller + "/allow_partial_joints_goal", partial);
  for (size_t i = 0; i < names.size(); ++i) {
    if (!named[i] && !partial) missing += (missing.empty() ? "'" : ", '") + names[i] + "'";
  }
  if (goal->trajectory.joint_names.empty()) missing = "all (the trajectory names no joints)";
  if (!unknown.empty() || !twice.empty() || !missing.empty()) {
    std::string why = "joints on the goal do not match the controller's (" + joinNames(names) + "):";
    if (!unknown.empty()) why += " unknown " + unknown + ";";
    if (!missing.empty()) why += " missing " + missing + ";";
    if (!twice.empty()) why += " named twice " + twice + ";";
    why.pop_back();
    reject(FollowJointTrajectoryResult::INVALID_JOINTS, why);
    return;
  }
  int code = 0;
  const std::string why = acceptTrajectoryLocked(*goal, index, &code);
  if (!why.empty()) {
    reject(code, why);
    return;
  }
  preemptLocked("preempted by a new goal");
  trajectory_goal_ = gh;
  mode_ = Mode::trajectory;
  gh.setAccepted("following the trajectory");
}

std::string JointGroupServer::waypointsLocked(const control_msgs::FollowJointTrajectoryGoal& goal,
                                              const std::vector<int>& index, std::vector<Waypoint>* waypoints) const {
  const auto names = chain_.names();
  const size_t n = names.size(), m = index.size();
  for (size_t k = 0; k < goal.trajectory.points.size(); ++k) {
    const auto& p = goal.trajectory.points[k];
    const std::string point = "point " + std::to_string(k);
    if (p.positions.size() != m) {
      return point + " has " + std::to_string(p.positions.size()) + " positions for " + std::to_string(m) + " joints";
    }
    if ((!p.velocities.empty() && p.velocities.size() != m) || (!p.accelerations.empty() && p.accelerations.size() != m)) {
      return point + " has velocities or accelerations for a different number of joints than its positions";
    }
    if (!allFinite(p.positions) || !allFinite(p.velocities) || !allFinite(p.accelerations)) {
      return point + " has a value that is not finite";
    }
    Waypoint w;
    w.time = p.time_from_start.toSec();
    w.positions = q_;  // joints the goal leaves out (allow_partial_joints_goal) hold their position
    if (!p.velocities.empty()) w.velocities.assign(n, 0.0);
    if (!p.accelerations.empty()) w.accelerations.assign(n, 0.0);
    for (size_t j = 0; j < m; ++j) {
      w.positions[index[j]] = p.positions[j];
      if (!p.velocities.empty()) w.velocities[index[j]] = p.velocities[j];
      if (!p.accelerations.empty()) w.accelerations[index[j]] = p.accelerations[j];
    }
    const std::string limits = chain_.limitViolation(w.positions);
    if (!limits.empty()) return point + ": " + limits;
    if (!waypoints->empty() && !(w.time > waypoints->back().time)) {
      return point + format(": time_from_start %.3f s does not follow the previous point's %.3f s", w.time,
                            waypoints->back().time);
    }
    if (w.time < 0) return point + format(": negative time_from_start %.3f s", w.time);
    if (w.time == 0) {  // a trajectory may begin with the state it starts from (MoveIt's do)
      for (size_t j = 0; j < n; ++j) {
        if (std::abs(w.positions[j] - q_[j]) > 1e-3) {
          return point + " at time_from_start 0 puts '" + names[j] +
                 format("' at %.4f rad, but it is at %.4f rad: a trajectory starts where the joints are",
                        w.positions[j], q_[j]);
        }
      }
      continue;
    }
    waypoints->push_back(std::move(w));
  }
  if (waypoints->empty()) return "the trajectory has no point after time 0";
  return "";
}

std::string JointGroupServer::velocityViolation(const SplineTrajectory& spline) const {
  const auto names = chain_.names();
  for (size_t j = 0; j < names.size(); ++j) {
    double when = 0;
    const double peak = spline.peakVelocity(j, &when);
    if (peak > chain_.joints[j].max_velocity * (1 + 1e-6)) {
      return "joint '" + names[j] +
             format("' would move at %.4f rad/s (t = %.3f s), above its velocity limit %.4f rad/s: give the "
                    "trajectory more time",
                    peak, when, chain_.joints[j].max_velocity);
    }
  }
  return "";
}

void JointGroupServer::tolerancesOf(const control_msgs::FollowJointTrajectoryGoal& goal, std::vector<double>* path,
                                    std::vector<double>* at_goal) const {
  // The goal's where it gives one (> 0: that, < 0: none, 0: the controller's).
  const auto names = chain_.names();
  const std::string constraints = config_.controller + "/constraints/";
  path->assign(names.size(), 0.0);
  at_goal->assign(names.size(), 0.0);
  for (size_t j = 0; j < names.size(); ++j) {
    (*path)[j] = param(constraints + names[j] + "/trajectory", 0.0);
    (*at_goal)[j] = param(constraints + names[j] + "/goal", 0.0);
  }
  auto apply = [&](const std::vector<control_msgs::JointTolerance>& given, std::vector<double>* tolerance) {
    for (const auto& t : given) {
      const auto it = std::find(names.begin(), names.end(), t.name);
      if (it == names.end()) {
        ROS_WARN("%s: ignoring a tolerance for joint '%s', which the controller does not have",
                 trajectory_action_.c_str(), t.name.c_str());
        continue;
      }
      if (t.position > 0) (*tolerance)[it - names.begin()] = t.position;
      if (t.position < 0) (*tolerance)[it - names.begin()] = 0.0;
    }
  };
  apply(goal.path_tolerance, path);
  apply(goal.goal_tolerance, at_goal);
}

void JointGroupServer::planFaultsLocked() {
  // A joint sticking part way, a joint settling off its goal.
  stuck_joint_ = -1;
  stuck_ = false;
  const double p_fault = param(config_.abort_probability_param, 0.0);
  if (p_fault > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < p_fault) {
    double most = -1;
    for (size_t j = 0; j < q_.size(); ++j) {
      const double d = std::abs(spline_.goal()[j] - q_[j]);
      if (d > most) {
        most = d;
        stuck_joint_ = static_cast<int>(j);
      }
    }
    stuck_at_ = std::uniform_real_distribution<double>(0.2, 0.8)(rng_);
  }
  settle_joint_ = -1;
  std::string settle_joint;
  nh_.getParam(config_.settle_joint_param, settle_joint);
  const auto names = chain_.names();
  const auto it = std::find(names.begin(), names.end(), settle_joint);
  if (it != names.end()) {
    settle_joint_ = static_cast<int>(it - names.begin());
    settle_error_ = param(config_.settle_error_param, 0.0);
  }
}

std::string JointGroupServer::acceptTrajectoryLocked(const control_msgs::FollowJointTrajectoryGoal& goal,
                                                     const std::vector<int>& index, int* code) {
  *code = FollowJointTrajectoryResult::INVALID_GOAL;
  std::vector<Waypoint> waypoints;
  std::string why = waypointsLocked(goal, index, &waypoints);
  if (!why.empty()) return why;
  const size_t n = q_.size();
  SplineTrajectory spline(q_, qd_, std::vector<double>(n, 0.0), waypoints);
  why = velocityViolation(spline);
  if (!why.empty()) return why;
  // When it starts: now, or at the header's stamp (simulated time runs time_scale times faster).
  double start = 0;
  if (!goal.trajectory.header.stamp.isZero()) {
    start = (ros::Time::now() - goal.trajectory.header.stamp).toSec() * time_scale_;
    if (start >= spline.duration()) {
      *code = FollowJointTrajectoryResult::OLD_HEADER_TIMESTAMP;
      return format("the trajectory (header.stamp %.3f s, %.3f s long) ended before it arrived (now %.3f s)",
                    goal.trajectory.header.stamp.toSec(), spline.duration(), ros::Time::now().toSec());
    }
  }
  std::vector<double> path, at_goal;
  tolerancesOf(goal, &path, &at_goal);
  const std::string constraints = config_.controller + "/constraints/";
  const double goal_time =
      goal.goal_time_tolerance.toSec() > 0 ? goal.goal_time_tolerance.toSec() : param(constraints + "goal_time", 0.0);
  if (goal.goal_time_tolerance.toSec() < 0) return format("negative goal_time_tolerance %.3f s", goal.goal_time_tolerance.toSec());

  // Accepted.
  spline_ = std::move(spline);
  path_tolerance_ = path;
  goal_tolerance_ = at_goal;
  goal_time_ = goal_time;
  t_ = start;
  planFaultsLocked();
  *code = 0;
  return "";
}

void JointGroupServer::onTrajectoryCancel(TrajectoryServer::GoalHandle gh) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (mode_ == Mode::trajectory && gh == trajectory_goal_) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    FollowJointTrajectoryResult r;
    r.error_string = "canceled: stopped where the joints were";
    trajectory_goal_.setCanceled(r, r.error_string);
    mode_ = Mode::idle;
  }
}

void JointGroupServer::endTrajectoryLocked(int code, const std::string& text) {
  FollowJointTrajectoryResult r;
  r.error_code = code;
  r.error_string = text;
  std::fill(qd_.begin(), qd_.end(), 0.0);
  if (code == FollowJointTrajectoryResult::SUCCESSFUL) {
    trajectory_goal_.setSucceeded(r, text);
  } else {
    ROS_WARN("%s: aborted: %s", trajectory_action_.c_str(), text.c_str());
    trajectory_goal_.setAborted(r, text);
  }
  mode_ = Mode::idle;
}

void JointGroupServer::stepTrajectoryLocked(double sim_dt) {
  t_ += sim_dt;
  const auto names = chain_.names();
  const double duration = spline_.duration();
  std::vector<double> desired, desired_velocity;
  spline_.sample(t_, &desired, &desired_velocity);
  std::vector<double> actual = desired;
  const double progress = duration > 0 ? std::min(1.0, std::max(0.0, t_ / duration)) : 1.0;
  if (settle_joint_ >= 0) actual[settle_joint_] += settle_error_ * progress;
  if (stuck_joint_ >= 0) {
    if (!stuck_ && progress >= stuck_at_) {
      stuck_ = true;
      stuck_position_ = q_[stuck_joint_];
    }
    if (stuck_) actual[stuck_joint_] = stuck_position_;
  }
  const std::vector<double> previous = q_;
  q_ = actual;
  for (size_t j = 0; j < q_.size(); ++j) qd_[j] = sim_dt > 0 ? (q_[j] - previous[j]) / sim_dt : 0.0;

  if (t_ > 0 && t_ < duration) {
    for (size_t j = 0; j < q_.size(); ++j) {
      const double error = std::abs(actual[j] - desired[j]);
      if (path_tolerance_[j] > 0 && error > path_tolerance_[j]) {
        endTrajectoryLocked(FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED,
                            "path tolerance violated: joint '" + names[j] +
                                format("' is %.4f rad from the trajectory (path tolerance %.4f rad) at "
                                       "t = %.3f s of %.3f s",
                                       error, path_tolerance_[j], t_, duration));
        return;
      }
    }
  }
  if (t_ >= duration) {
    int worst = -1;
    double worst_error = 0;
    for (size_t j = 0; j < q_.size(); ++j) {
      const double error = std::abs(q_[j] - spline_.goal()[j]);
      if (goal_tolerance_[j] > 0 && error > goal_tolerance_[j] && error - goal_tolerance_[j] > worst_error) {
        worst = static_cast<int>(j);
        worst_error = error - goal_tolerance_[j];
      }
    }
    if (worst < 0) {
      endTrajectoryLocked(FollowJointTrajectoryResult::SUCCESSFUL, "");
      return;
    }
    if (t_ - duration >= goal_time_) {
      endTrajectoryLocked(FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED,
                          "goal tolerance violated: joint '" + names[worst] +
                              format("' is %.4f rad from its goal (goal tolerance %.4f rad) %.3f s after the "
                                     "trajectory's end (goal_time_tolerance %.3f s)",
                                     std::abs(q_[worst] - spline_.goal()[worst]), goal_tolerance_[worst],
                                     t_ - duration, goal_time_));
      return;
    }
  }
  control_msgs::FollowJointTrajectoryFeedback fb;
  fb.header.stamp = ros::Time::now();
  fb.joint_names = names;
  fb.desired.positions = desired;
  fb.desired.velocities = desired_velocity;
  fb.desired.time_from_start = ros::Duration(std::max(0.0, t_));
  fb.actual.positions = q_;
  fb.actual.velocities = qd_;
  fb.actual.time_from_start = fb.desired.time_from_start;
  fb.error.time_from_start = fb.desired.time_from_start;
  for (size_t j = 0; j < q_.size(); ++j) {
    fb.error.positions.push_back(desired[j] - q_[j]);
    fb.error.velocities.push_back(desired_velocity[j] - qd_[j]);
  }
  trajectory_goal_.publishFeedback(fb);
}

// ---- both ----

void JointGroupServer::step(double sim_dt) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (mode_ == Mode::idle) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    return;
  }
  if (mode_ == Mode::trajectory) {
    stepTrajectoryLocked(sim_dt);
    return;
  }
  t_ += sim_dt;
  const std::vector<double> previous = q_;
  q_ = move_trajectory_.positionAt(t_);
  for (size_t i = 0; i < q_.size(); ++i) qd_[i] = sim_dt > 0 ? (q_[i] - previous[i]) / sim_dt : 0.0;
  const double progress = move_trajectory_.progressAt(t_);
  if (progress >= abort_at_) {
    std::ostringstream why;
    why << "simulated fault: the controller aborted the motion at " << static_cast<int>(progress * 100)
        << "% of the trajectory";
    std::fill(qd_.begin(), qd_.end(), 0.0);
    move_goal_.setAborted(moveResultLocked(why.str()), why.str());
    mode_ = Mode::idle;
    return;
  }
  if (progress >= 1.0) {
    std::fill(qd_.begin(), qd_.end(), 0.0);
    move_goal_.setSucceeded(moveResultLocked("reached"), "reached");
    mode_ = Mode::idle;
    return;
  }
  friend_msgs::MoveJointsFeedback fb;
  fb.joint_names = chain_.names();
  fb.positions = q_;
  fb.progress = progress;
  move_goal_.publishFeedback(fb);
}

void JointGroupServer::setTimeScale(double scale) {
  std::lock_guard<std::mutex> lock(mutex_);
  time_scale_ = scale;
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
  return mode_ != Mode::idle;
}

}  // namespace friend_hw_sim
