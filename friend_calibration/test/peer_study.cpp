#include "peer_study.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>

#include "friend_hw_sim/true_robot.h"
#include "imagenets/package_file.h"
#include "imagenets/vision/target.h"
#include "imagenets_calibration/bundle_adjustment.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/hand_eye_peers.h"

namespace imagenets_calibration {

namespace {

constexpr double kDeg = M_PI / 180.0;

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

imagenets::render::CameraModel renderModel(const PinholeCamera& c, int width, int height) {
  imagenets::render::CameraModel m;
  m.width = width;
  m.height = height;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) m.K(r, k) = c.K(r, k);
  m.D = c.distortion;
  return m;
}

// `n` arm poses around the calibration pose that show the whole marker in the left image (a
// tenth of the image from its borders, at most 55 deg oblique), the head at its calibration pose.
std::vector<std::vector<double>> armPoses(const RobotModel& model, const PinholeCamera& camera,
                                          const std::vector<double>& head_q, int n, std::mt19937& rng) {
  const auto& d = model.description();
  const std::vector<Eigen::Vector3d> corners = markerDefinedPoints(d.marker_size);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::vector<double>> poses;
  const Eigen::Isometry3d camera_in_base = model.leftCamera(head_q);
  for (int attempt = 0; attempt < 100000 && static_cast<int>(poses.size()) < n; ++attempt) {
    std::vector<double> q = d.arm_calibration_pose;
    for (size_t j = 0; j < q.size(); ++j) q[j] += (j == 0 ? 8.0 : 20.0) * kDeg * u(rng);
    bool ok = true;
    for (size_t j = 0; j < q.size() && ok; ++j) ok = q[j] >= d.arm.joints[j].min && q[j] <= d.arm.joints[j].max;
    if (!ok) continue;
    const Eigen::Isometry3d m = camera_in_base.inverse() * model.marker(q);
    if (-m.linear().col(2).dot(m.translation().normalized()) < std::cos(55 * kDeg)) continue;
    const double margin = 0.1 * d.image_width;
    for (const auto& p : corners) {
      const Eigen::Vector3d pc = m * p;
      const Eigen::Vector2d uv = camera.project(pc);
      ok = ok && pc.z() > 0 && uv.x() > margin && uv.y() > margin && uv.x() < d.image_width - margin &&
           uv.y() < d.image_height - margin;
    }
    if (ok) poses.push_back(q);
  }
  return poses;
}

}  // namespace

std::string PeerStudyRow::label() const {
  std::ostringstream os;
  os << noise_px << " px, " << poses << " poses";
  if (bad_fraction > 0) os << ", " << std::lround(100 * bad_fraction) << " % bad";
  return os.str();
}

std::vector<PeerStudyRow> peerStudyRows() {
  return {{0.2, 10, 0.0}, {0.5, 10, 0.0}, {1.0, 10, 0.0}, {0.5, 20, 0.1}, {0.5, 5, 0.0}, {0.5, 20, 0.0}};
}

PeerStudyResult runPeerStudy(const PeerStudyRow& row, int trials) {
  const RobotModel model(robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml")));
  const auto& d = model.description();
  const StereoCameras cameras = *stereoCamerasOf(d, nullptr);
  const auto camera = renderModel(cameras.left, d.image_width, d.image_height);
  const std::vector<Eigen::Vector3d> points = markerDefinedPoints(d.marker_size);
  const std::vector<double> head_q = d.head_calibration_pose;

  PeerStudyResult out;
  out.row = row;
  out.trials = trials;
  std::vector<std::vector<double>> mm, deg;
  auto record = [&](size_t method, const std::string& name, bool ok, const Eigen::Isometry3d& found,
                    const Eigen::Isometry3d& truth) {
    if (out.methods.size() <= method) {
      out.methods.push_back(name);
      mm.emplace_back();
      deg.emplace_back();
      out.failures.push_back(0);
    }
    if (!ok) {
      ++out.failures[method];
      return;
    }
    mm[method].push_back(1000 * (found.translation() - truth.translation()).norm());
    deg[method].push_back(angleBetween(found, truth) / kDeg);
  };

  for (int seed = 1; seed <= trials; ++seed) {
    // The true robot: the simulator's random head mount and marker offset, exact joints.
    auto error = friend_hw_sim::loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), d, seed);
    std::fill(error.arm_joint_offsets.begin(), error.arm_joint_offsets.end(), 0.0);
    std::fill(error.head_joint_offsets.begin(), error.head_joint_offsets.end(), 0.0);
    const RobotModel truth(friend_hw_sim::applyTrueError(d, error));
    const Eigen::Isometry3d true_camera = truth.leftCamera(head_q);
    std::mt19937 rng(7919 * seed + static_cast<unsigned>(1000 * row.noise_px) + 31 * row.poses);
    const auto arms = armPoses(truth, cameras.left, head_q, row.poses, rng);
    const int bad = row.bad_fraction > 0 ? std::max(1, static_cast<int>(std::lround(row.bad_fraction * arms.size()))) : 0;
    std::normal_distribution<double> noise(0, row.noise_px);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI);

    std::vector<Sample> samples;
    std::vector<HandEyeSample> peer_samples;
    for (size_t k = 0; k < arms.size(); ++k) {
      const Eigen::Isometry3d marker_in_camera = true_camera.inverse() * truth.marker(arms[k]);
      imagenets::target::TargetDetection det;
      for (size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector2d uv = cameras.left.project(marker_in_camera * points[i]);
        det.points.emplace_back(uv.x() + noise(rng), uv.y() + noise(rng));
        det.object_points.push_back(points[i]);
        det.ids.push_back(static_cast<int>(i));
      }
      if (static_cast<int>(k) < bad) {  // the first `bad` samples: a reflection moves two corners
        for (int i : {1, 5}) {
          const double a = angle(rng);
          det.points[i] += cv::Point2d(3.0 * std::cos(a), 3.0 * std::sin(a));
        }
      }
      imagenets::target::fitTargetPose(camera, {}, &det);
      Sample s;
      s.arm_q = arms[k];
      s.head_q = head_q;
      s.left.found = true;
      s.left.pose = det.pose;
      s.left.confidence = 1.0;
      s.left.reprojection_error = det.reprojection_error;
      for (const auto& p : det.points) s.left.points.emplace_back(p.x, p.y);
      s.left.point_ids = det.ids;
      s.left.object_points = det.object_points;
      s.right.found = false;
      s.right.reason = "the study's camera is the left one";
      samples.push_back(s);
      HandEyeSample h;
      h.base_tcp = model.tcp(arms[k]);  // the joints are exact: nominal = true kinematics
      h.camera_target = det.pose;
      peer_samples.push_back(h);
    }

    // Ours: the joint method as calibrate() runs it (3D points, then the pixel-level fit), with
    // the reprojection gate relative to the noise the detections show.
    FusionLimits limits;
    limits.max_reprojection_error = 5.0;
    const Result r = calibrate(model, samples, "joint", limits, CombineOptions());
    record(0, "ours", r.success, r.success ? calibratedModel(model, r).leftCamera(head_q) : Eigen::Isometry3d::Identity(),
           true_camera);
    const auto peers = eyeToHandPeers(peer_samples);
    for (size_t m = 0; m < peers.size(); ++m) record(m + 1, peers[m].method, peers[m].ok, peers[m].base_camera, true_camera);
  }
  for (size_t m = 0; m < out.methods.size(); ++m) {
    out.median_mm.push_back(median(mm[m]));
    out.median_deg.push_back(median(deg[m]));
    out.max_mm.push_back(mm[m].empty() ? std::nan("") : *std::max_element(mm[m].begin(), mm[m].end()));
    out.max_deg.push_back(deg[m].empty() ? std::nan("") : *std::max_element(deg[m].begin(), deg[m].end()));
  }
  return out;
}

std::string peerStudyMarkdown(const std::vector<PeerStudyResult>& results) {
  std::ostringstream os;
  if (results.empty()) return "";
  os << "| samples |";
  for (const auto& m : results.front().methods) os << " " << m << " |";
  os << "\n|---|";
  for (size_t m = 0; m < results.front().methods.size(); ++m) os << "---|";
  os << "\n" << std::fixed;
  for (const auto& r : results) {
    os << "| " << r.row.label() << " |";
    for (size_t m = 0; m < r.methods.size(); ++m) {
      os << " " << std::setprecision(2) << r.median_mm[m] << " mm / " << std::setprecision(3) << r.median_deg[m]
         << " deg";
      if (r.failures[m]) os << " (" << r.failures[m] << " failed)";
      os << " |";
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace imagenets_calibration
