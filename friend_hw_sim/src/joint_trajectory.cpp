#include "friend_hw_sim/joint_trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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

namespace {

// Coefficients of the polynomial from (p0, v0, a0) at 0 to (p1, v1, a1) at T, of the order the
// end state gives (as joint_trajectory_controller interpolates).
std::array<double, 6> segmentCoefficients(double T, double p0, double v0, double a0, double p1, bool has_v, double v1,
                                          bool has_a, double a1) {
  std::array<double, 6> c{};
  c[0] = p0;
  const double d = p1 - p0;
  if (has_a) {  // quintic
    c[1] = v0;
    c[2] = a0 / 2;
    c[3] = (20 * d - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T * T) / (2 * std::pow(T, 3));
    c[4] = (-30 * d + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T * T) / (2 * std::pow(T, 4));
    c[5] = (12 * d - 6 * (v1 + v0) * T - (a0 - a1) * T * T) / (2 * std::pow(T, 5));
  } else if (has_v) {  // cubic
    c[1] = v0;
    c[2] = (3 * d - (2 * v0 + v1) * T) / (T * T);
    c[3] = (-2 * d + (v0 + v1) * T) / std::pow(T, 3);
  } else {  // linear
    c[1] = d / T;
  }
  return c;
}

}  // namespace

SplineTrajectory::SplineTrajectory(const std::vector<double>& q0, const std::vector<double>& v0,
                                   const std::vector<double>& a0, const std::vector<Waypoint>& waypoints)
    : start_(q0), goal_(q0) {
  const size_t n = q0.size();
  if (v0.size() != n || a0.size() != n) throw std::invalid_argument("SplineTrajectory: start state sizes differ");
  std::vector<double> p = q0, v = v0, a = a0;
  double t = 0;
  for (size_t k = 0; k < waypoints.size(); ++k) {
    const Waypoint& w = waypoints[k];
    const std::string which = "SplineTrajectory: waypoint " + std::to_string(k);
    if (w.positions.size() != n) throw std::invalid_argument(which + " has the wrong number of positions");
    if (!w.velocities.empty() && w.velocities.size() != n) throw std::invalid_argument(which + ": velocities");
    if (!w.accelerations.empty() && w.accelerations.size() != n) throw std::invalid_argument(which + ": accelerations");
    if (!(w.time > t)) throw std::invalid_argument(which + ": times must increase strictly from above 0");
    const bool has_v = !w.velocities.empty(), has_a = has_v && !w.accelerations.empty();
    Segment s;
    s.start = t;
    s.end = w.time;
    for (size_t j = 0; j < n; ++j) {
      s.coefficients.push_back(segmentCoefficients(w.time - t, p[j], v[j], a[j], w.positions[j],
                                                   has_v, has_v ? w.velocities[j] : 0.0, has_a,
                                                   has_a ? w.accelerations[j] : 0.0));
    }
    segments_.push_back(std::move(s));
    p = w.positions;
    v = has_v ? w.velocities : std::vector<double>(n, 0.0);
    a = has_a ? w.accelerations : std::vector<double>(n, 0.0);
    t = w.time;
  }
  goal_ = p;
}

void SplineTrajectory::sample(double t, std::vector<double>* q, std::vector<double>* qd) const {
  const size_t n = goal_.size();
  q->assign(n, 0.0);
  if (qd) qd->assign(n, 0.0);
  if (segments_.empty()) {
    *q = goal_;
    return;
  }
  if (t <= 0) {  // the start state
    *q = start_;
    if (qd) {
      for (size_t j = 0; j < n; ++j) (*qd)[j] = segments_.front().coefficients[j][1];
    }
    return;
  }
  if (t >= duration()) {  // at rest on the last waypoint, exactly
    *q = goal_;
    return;
  }
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                                   [](double x, const Segment& s) { return x < s.end; });
  const Segment& s = it == segments_.end() ? segments_.back() : *it;
  const double tau = t - s.start;
  for (size_t j = 0; j < n; ++j) {
    const auto& c = s.coefficients[j];
    (*q)[j] = c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))));
    if (qd) (*qd)[j] = c[1] + tau * (2 * c[2] + tau * (3 * c[3] + tau * (4 * c[4] + tau * 5 * c[5])));
  }
}

double SplineTrajectory::peakVelocity(size_t j, double* at) const {
  double peak = 0, when = 0;
  for (const Segment& s : segments_) {
    const auto& c = s.coefficients.at(j);
    constexpr int kSamples = 200;
    for (int i = 0; i <= kSamples; ++i) {
      const double tau = (s.end - s.start) * i / kSamples;
      const double v = std::abs(c[1] + tau * (2 * c[2] + tau * (3 * c[3] + tau * (4 * c[4] + tau * 5 * c[5]))));
      if (v > peak) {
        peak = v;
        when = s.start + tau;
      }
    }
  }
  if (at) *at = when;
  return peak;
}

}  // namespace friend_hw_sim
