#include "imagenets/vision/frames.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

namespace imagenets {
namespace frames {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void requireFinite(double v, const std::string& what, const char* component) {
  if (!std::isfinite(v)) throw FrameError(what + ": " + component + " is " + num(v) + " (not finite)");
}

}  // namespace

Eigen::Quaterniond toQuaternion(const geometry_msgs::Quaternion& q, const std::string& what) {
  requireFinite(q.x, what, "orientation.x");
  requireFinite(q.y, what, "orientation.y");
  requireFinite(q.z, what, "orientation.z");
  requireFinite(q.w, what, "orientation.w");
  Eigen::Quaterniond e(q.w, q.x, q.y, q.z);
  const double norm = e.norm();
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    throw FrameError(what + ": quaternion (x " + num(q.x) + ", y " + num(q.y) + ", z " + num(q.z) + ", w " +
                     num(q.w) + ") has norm " + num(norm) + ", not 1");
  }
  return e.normalized();
}

Eigen::Vector3d toVector(const geometry_msgs::Vector3& v, const std::string& what) {
  requireFinite(v.x, what, "x");
  requireFinite(v.y, what, "y");
  requireFinite(v.z, what, "z");
  return {v.x, v.y, v.z};
}

Eigen::Vector3d toVector(const geometry_msgs::Point& p, const std::string& what) {
  requireFinite(p.x, what, "position.x");
  requireFinite(p.y, what, "position.y");
  requireFinite(p.z, what, "position.z");
  return {p.x, p.y, p.z};
}

Eigen::Isometry3d toIsometry(const geometry_msgs::Pose& pose, const std::string& what) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = toQuaternion(pose.orientation, what).toRotationMatrix();
  t.translation() = toVector(pose.position, what);
  return t;
}

Eigen::Isometry3d toIsometry(const geometry_msgs::Transform& transform, const std::string& what) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = toQuaternion(transform.rotation, what).toRotationMatrix();
  t.translation() = toVector(transform.translation, what + " translation");
  return t;
}

geometry_msgs::Quaternion toQuaternionMsg(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  m.w = q.w();
  return m;
}

geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

geometry_msgs::Point toPointMsg(const Eigen::Vector3d& v) {
  geometry_msgs::Point m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

geometry_msgs::Pose toPose(const Eigen::Isometry3d& t) {
  geometry_msgs::Pose p;
  p.position = toPointMsg(t.translation());
  p.orientation = toQuaternionMsg(Eigen::Quaterniond(t.rotation()).normalized());
  return p;
}

geometry_msgs::Pose toPose(const geometry_msgs::Transform& t) {
  geometry_msgs::Pose p;
  p.position.x = t.translation.x;
  p.position.y = t.translation.y;
  p.position.z = t.translation.z;
  p.orientation = t.rotation;
  return p;
}

geometry_msgs::Transform toTransform(const Eigen::Isometry3d& t) {
  geometry_msgs::Transform m;
  m.translation = toVector3Msg(t.translation());
  m.rotation = toQuaternionMsg(Eigen::Quaterniond(t.rotation()).normalized());
  return m;
}

geometry_msgs::TransformStamped toTransformStamped(const Eigen::Isometry3d& t, const std::string& parent,
                                                   const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped m;
  m.header.stamp = stamp;
  m.header.frame_id = parent;
  m.child_frame_id = child;
  m.transform = toTransform(t);
  return m;
}

double rotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  // |<a,b>| = cos(angle/2), independent of the sign of either quaternion.
  const double c = std::min(1.0, std::abs(a.normalized().dot(b.normalized())));
  return 2.0 * std::acos(c);
}

Eigen::Quaterniond meanRotation(const std::vector<Eigen::Quaterniond>& rotations, const std::vector<double>& weights) {
  if (rotations.empty()) throw FrameError("mean rotation of an empty set");
  if (!weights.empty() && weights.size() != rotations.size()) {
    throw FrameError("mean rotation: " + std::to_string(weights.size()) + " weights for " +
                     std::to_string(rotations.size()) + " rotations");
  }
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  for (size_t i = 0; i < rotations.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!(w >= 0) || !std::isfinite(w)) throw FrameError("mean rotation: weight " + std::to_string(i) + " is " + num(w));
    const Eigen::Vector4d q = rotations[i].normalized().coeffs();  // x, y, z, w; q q^T is sign-free
    m += w * q * q.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(m);
  Eigen::Vector4d v = solver.eigenvectors().col(3);  // eigenvalues ascending: the largest is last
  if (v(3) < 0) v = -v;
  return Eigen::Quaterniond(v(3), v(0), v(1), v(2)).normalized();
}

double median(std::vector<double> values) {
  if (values.empty()) throw FrameError("median of an empty set");
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

Eigen::Vector3d medianTranslation(const std::vector<Eigen::Vector3d>& translations) {
  if (translations.empty()) throw FrameError("median translation of an empty set");
  Eigen::Vector3d result;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    values.reserve(translations.size());
    for (const auto& t : translations) values.push_back(t(axis));
    result(axis) = median(std::move(values));
  }
  return result;
}

FusionResult fusePoses(const std::optional<Eigen::Isometry3d>& first, const std::optional<Eigen::Isometry3d>& second,
                       const FusionLimits& limits) {
  FusionResult r;
  r.position_difference = std::numeric_limits<double>::quiet_NaN();
  r.angle_difference = std::numeric_limits<double>::quiet_NaN();
  if (!first && !second) {
    r.reason = "neither pose is valid";
    return r;
  }
  if (!first || !second) {
    r.valid = true;
    r.source = first ? FusionResult::Source::First : FusionResult::Source::Second;
    r.pose = first ? *first : *second;
    r.reason = first ? "only the first pose is valid" : "only the second pose is valid";
    return r;
  }
  const Eigen::Quaterniond q1(first->rotation()), q2(second->rotation());
  r.position_difference = (first->translation() - second->translation()).norm();
  r.angle_difference = rotationAngle(q1, q2);
  if (r.position_difference > limits.max_position_difference) {
    r.reason = "poses disagree: positions " + num(r.position_difference) + " m apart (limit " +
               num(limits.max_position_difference) + " m)";
    return r;
  }
  if (r.angle_difference > limits.max_angle_difference) {
    r.reason = "poses disagree: rotations " + num(r.angle_difference) + " rad apart (limit " +
               num(limits.max_angle_difference) + " rad)";
    return r;
  }
  r.valid = true;
  r.source = FusionResult::Source::Both;
  r.pose = Eigen::Isometry3d::Identity();
  r.pose.linear() = meanRotation({q1, q2}).toRotationMatrix();
  r.pose.translation() = 0.5 * (first->translation() + second->translation());
  r.reason = "mean of both poses";
  return r;
}

}  // namespace frames
}  // namespace imagenets
