#include "friend_calibration/bundle_adjustment.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "imagenets/vision/frames.h"
#include "imagenets/vision/read_camera_info.h"
#include "imagenets/vision/render.h"

namespace friend_calibration {
namespace {

template <typename T>
using Mat4 = Eigen::Matrix<T, 4, 4>;

Eigen::Matrix4d matrixOf(const Eigen::Isometry3d& t) { return t.matrix(); }

// A frame (rotation R0, translation t0) perturbed on the left by (dt, w): (exp(w) R0, t0 + dt).
template <typename T>
Mat4<T> perturbed(const Eigen::Isometry3d& base, const T* p) {
  Eigen::Matrix<T, 3, 3> rw;
  ceres::AngleAxisToRotationMatrix(p + 3, rw.data());  // column major, as Eigen's default
  Mat4<T> m = Mat4<T>::Identity();
  m.template topLeftCorner<3, 3>() = rw * base.rotation().cast<T>();
  for (int i = 0; i < 3; ++i) m(i, 3) = T(base.translation()[i]) + p[i];
  return m;
}

template <typename T>
Mat4<T> inverseOf(const Mat4<T>& m) {
  Mat4<T> inv = Mat4<T>::Identity();
  inv.template topLeftCorner<3, 3>() = m.template topLeftCorner<3, 3>().transpose();
  inv.template topRightCorner<3, 1>() = -(m.template topLeftCorner<3, 3>().transpose() * m.template topRightCorner<3, 1>());
  return inv;
}

template <typename T>
Eigen::Matrix<T, 2, 1> projectPoint(const PinholeCamera& c, const Eigen::Matrix<T, 3, 1>& p) {
  const T x = p.x() / p.z(), y = p.y() / p.z();
  auto k = [&](size_t i) { return i < c.distortion.size() ? c.distortion[i] : 0.0; };
  const T r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
  const T radial = (T(1) + T(k(0)) * r2 + T(k(1)) * r4 + T(k(4)) * r6) / (T(1) + T(k(5)) * r2 + T(k(6)) * r4 + T(k(7)) * r6);
  const T xd = x * radial + T(2 * k(2)) * x * y + T(k(3)) * (r2 + T(2) * x * x);
  const T yd = y * radial + T(k(2)) * (r2 + T(2) * y * y) + T(2 * k(3)) * x * y;
  return {T(c.K(0, 0)) * xd + T(c.K(0, 1)) * yd + T(c.K(0, 2)), T(c.K(1, 1)) * yd + T(c.K(1, 2))};
}

// Which joints' zero offsets are estimated (as the joint method: arm 2..n-1, head tilt..n).
struct OffsetLayout {
  std::vector<size_t> arm, head;
  explicit OffsetLayout(const RobotModel& m) {
    const auto& d = m.description();
    for (size_t j = 1; j + 1 < d.arm.joints.size(); ++j) arm.push_back(j);
    for (size_t j = 1; j < d.head.joints.size(); ++j) head.push_back(j);
  }
};

// Points of one detection, residuals in noise sigmas. Parameters: fixed point (6), marker
// offset (6), then the arm offsets and the head offsets when there are any.
struct DetectionResidual {
  const RobotModel* model;
  const OffsetLayout* layout;
  const PinholeCamera* camera;
  const Sample* sample;
  bool right;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> observed;
  Eigen::Isometry3d x0, m0;
  double sigma;
  bool robust;
  double huber;  // sigmas

  template <typename T>
  bool operator()(T const* const* p, T* residuals) const {
    const auto& d = model->description();
    const T* arm_off = layout->arm.empty() ? nullptr : p[2];
    const T* head_off = layout->head.empty() ? nullptr : p[layout->arm.empty() ? 2 : 3];
    auto offsetOf = [](const std::vector<size_t>& layout_joints, const T* values, size_t joint) {
      for (size_t i = 0; i < layout_joints.size(); ++i) {
        if (layout_joints[i] == joint) return values[i];
      }
      return T(0);
    };
    Mat4<T> tcp = matrixOf(d.arm.mount).cast<T>();
    for (size_t j = 0; j < d.arm.joints.size(); ++j) {
      tcp = tcp * robot_description::jointMatrix(d.arm.joints[j], T(sample->arm_q[j]) + offsetOf(layout->arm, arm_off, j));
    }
    tcp = tcp * matrixOf(d.tool.pose).cast<T>();
    Mat4<T> camera_in_base = perturbed(x0, p[0]);
    for (size_t j = 0; j < d.head.joints.size(); ++j) {
      camera_in_base = camera_in_base * robot_description::jointMatrix(d.head.joints[j], T(sample->head_q[j]) +
                                                                                             offsetOf(layout->head, head_off, j));
    }
    camera_in_base = camera_in_base * matrixOf(d.left_camera.pose).cast<T>();
    if (right) camera_in_base = camera_in_base * matrixOf(model->leftToRight()).cast<T>();
    const Mat4<T> marker_in_camera = inverseOf(camera_in_base) * tcp * perturbed(m0, p[1]);
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Matrix<T, 3, 1> pc =
          marker_in_camera.template topLeftCorner<3, 3>() * points[i].cast<T>() + marker_in_camera.template topRightCorner<3, 1>();
      const Eigen::Matrix<T, 2, 1> uv = projectPoint(*camera, pc);
      T ex = (uv.x() - T(observed[i].x())) / T(sigma), ey = (uv.y() - T(observed[i].y())) / T(sigma);
      // Huber loss per point, applied to the residual itself (its square is rho(|e|^2) =
      // 2 k |e| - k^2 beyond k): Ceres' loss functions act on a whole block, and one block per
      // detection evaluates the kinematic chain once for its 8 points.
      if (robust) {
        using std::sqrt;
        const T s = ex * ex + ey * ey;
        if (s > T(huber * huber)) {
          const T scale = sqrt(T(2 * huber) * sqrt(s) - T(huber * huber)) / sqrt(s);
          ex *= scale;
          ey *= scale;
        }
      }
      residuals[2 * i] = ex;
      residuals[2 * i + 1] = ey;
    }
    return true;
  }
};

// Weak priors, as the joint method's: marker offset near its drawing, encoder offsets small.
struct MarkerPrior {
  Eigen::Isometry3d m0, nominal;
  double translation, rotation;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    const Mat4<T> m = perturbed(m0, p);
    const Mat4<T> n = matrixOf(nominal).cast<T>();
    const Mat4<T> dm = inverseOf(n) * m;
    for (int i = 0; i < 3; ++i) r[i] = dm(i, 3) / T(translation);
    Eigen::Matrix<T, 3, 3> rot = dm.template topLeftCorner<3, 3>();
    T w[3];
    ceres::RotationMatrixToAngleAxis(rot.data(), w);
    for (int i = 0; i < 3; ++i) r[3 + i] = w[i] / T(rotation);
    return true;
  }
};
struct OffsetPrior {
  int n;
  double sigma;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    for (int i = 0; i < n; ++i) r[i] = p[0][i] / T(sigma);
    return true;
  }
};

double rmsMismatch(const PinholeCamera& c, const MarkerObservation& o, const std::vector<Eigen::Vector3d>& points) {
  double s = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = o.pose * points[i];
    if (!(p.z() > 0)) return std::numeric_limits<double>::infinity();
    s += (c.project(p) - o.points[i]).squaredNorm();
  }
  return std::sqrt(s / points.size());
}

PinholeCamera fromCameraModel(const imagenets::render::CameraModel& m) {
  PinholeCamera c;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) c.K(r, k) = m.K(r, k);
  }
  c.distortion = m.D;
  return c;
}

}  // namespace

Eigen::Vector2d PinholeCamera::project(const Eigen::Vector3d& p) const { return projectPoint<double>(*this, p); }

std::optional<StereoCameras> stereoCamerasOf(const robot_description::RobotDescription& d, std::string* why) {
  try {
    StereoCameras s;
    s.left = fromCameraModel(imagenets::render::CameraModel::fromCameraInfo(imagenets::readCameraInfo(d.left_camera_info)));
    s.right = fromCameraModel(imagenets::render::CameraModel::fromCameraInfo(imagenets::readCameraInfo(d.right_camera_info)));
    return s;
  } catch (const std::exception& e) {
    if (why) *why = e.what();
    return std::nullopt;
  }
}

std::vector<Eigen::Vector3d> markerDefinedPoints(double size, double border) {
  const double o = size / 2, i = size * (1 - 2 * border) / 2;
  return {{-o, o, 0}, {o, o, 0}, {o, -o, 0}, {-o, -o, 0}, {-i, i, 0}, {i, i, 0}, {i, -i, 0}, {-i, -i, 0}};
}

BundleAdjustment bundleAdjust(const RobotModel& model, const StereoCameras& cameras,
                              const std::vector<Eigen::Vector3d>& marker_points, const std::vector<const Sample*>& samples,
                              const Result& start, double max_reprojection_error, const BundleAdjustmentOptions& options) {
  BundleAdjustment out;
  const OffsetLayout layout(model);
  const auto& d = model.description();
  // The detections to fit: usable (as the chain uses them) and with points that fit their pose.
  struct Use {
    const Sample* sample;
    bool right;
  };
  std::vector<Use> uses;
  int mismatched = 0;
  for (const Sample* s : samples) {
    for (bool right : {false, true}) {
      const MarkerObservation& o = right ? s->right : s->left;
      if (!o.found || o.reprojection_error > max_reprojection_error || o.points.size() != marker_points.size()) continue;
      if (rmsMismatch(right ? cameras.right : cameras.left, o, marker_points) > options.max_point_mismatch) {
        ++mismatched;
        continue;
      }
      uses.push_back({s, right});
    }
  }
  if (uses.size() < 3) {
    out.message = "pixel-level fit skipped: " + std::to_string(uses.size()) + " detections with points that fit the camera model (" +
                  std::to_string(mismatched) + " do not)";
    return out;
  }

  // Start: the joint method's solution; parameters are perturbations of it.
  std::vector<double> arm_full = start.arm_joint_offsets, head_full = start.head_joint_offsets;
  arm_full.resize(d.arm.joints.size(), 0.0);
  head_full.resize(d.head.joints.size(), 0.0);
  double x[6] = {0, 0, 0, 0, 0, 0}, m[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> arm(layout.arm.size()), head(layout.head.size());
  for (size_t i = 0; i < layout.arm.size(); ++i) arm[i] = arm_full[layout.arm[i]];
  for (size_t i = 0; i < layout.head.size(); ++i) head[i] = head_full[layout.head[i]];
  const double prior_translation = 0.03, prior_rotation = 0.175, prior_offset = 0.0035;  // as solveJointly
  auto solve = [&](double sigma, bool with_covariance) {
    ceres::Problem problem;
    std::vector<double*> blocks{x, m};
    if (!arm.empty()) blocks.push_back(arm.data());
    if (!head.empty()) blocks.push_back(head.data());
    for (const Use& u : uses) {
      const MarkerObservation& o = u.right ? u.sample->right : u.sample->left;
      auto* f = new DetectionResidual{&model, &layout, u.right ? &cameras.right : &cameras.left, u.sample, u.right,
                                      marker_points, o.points, start.fixed_point, start.marker_offset, sigma, true,
                                      options.huber_sigmas};
      // Stride 18: FRIEND's 18 parameters in one pass of dual numbers.
      auto* cost = new ceres::DynamicAutoDiffCostFunction<DetectionResidual, 18>(f);
      cost->AddParameterBlock(6);
      cost->AddParameterBlock(6);
      if (!arm.empty()) cost->AddParameterBlock(static_cast<int>(arm.size()));
      if (!head.empty()) cost->AddParameterBlock(static_cast<int>(head.size()));
      cost->SetNumResiduals(static_cast<int>(2 * marker_points.size()));
      problem.AddResidualBlock(cost, nullptr, blocks);
    }
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<MarkerPrior, 6, 6>(
                                 new MarkerPrior{start.marker_offset, d.marker.pose, prior_translation, prior_rotation}),
                             nullptr, m);
    for (auto* values : {&arm, &head}) {
      if (values->empty()) continue;
      auto* prior = new ceres::DynamicAutoDiffCostFunction<OffsetPrior, 8>(
          new OffsetPrior{static_cast<int>(values->size()), prior_offset});
      prior->AddParameterBlock(static_cast<int>(values->size()));
      prior->SetNumResiduals(static_cast<int>(values->size()));
      problem.AddResidualBlock(prior, nullptr, values->data());
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = options.max_iterations;
    so.function_tolerance = 1e-12;
    so.parameter_tolerance = 1e-12;
    so.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      out.message = "pixel-level fit failed: " + summary.message;
      return false;
    }
    if (!with_covariance) return true;
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = -1;  // a direction the poses do not observe gets no (infinite) variance, not a crash
    ceres::Covariance covariance(co);
    std::vector<std::pair<const double*, const double*>> pairs;
    for (double* b : blocks) pairs.emplace_back(b, b);
    if (!covariance.Compute(pairs, &problem)) {
      out.message = "pixel-level fit: covariance not computable (the poses do not determine every parameter)";
      return true;
    }
    Eigen::Matrix<double, 6, 6, Eigen::RowMajor> c;
    covariance.GetCovarianceBlock(x, x, c.data());
    out.fixed_point_covariance = c;
    covariance.GetCovarianceBlock(m, m, c.data());
    out.marker_offset_covariance = c;
    out.arm_joint_offset_std.assign(d.arm.joints.size(), 0.0);
    out.head_joint_offset_std.assign(d.head.joints.size(), 0.0);
    if (!arm.empty()) {
      Eigen::MatrixXd a(arm.size(), arm.size());
      covariance.GetCovarianceBlock(arm.data(), arm.data(), a.data());
      for (size_t i = 0; i < arm.size(); ++i) out.arm_joint_offset_std[layout.arm[i]] = std::sqrt(std::max(0.0, a(i, i)));
    }
    if (!head.empty()) {
      Eigen::MatrixXd h(head.size(), head.size());
      covariance.GetCovarianceBlock(head.data(), head.data(), h.data());
      for (size_t i = 0; i < head.size(); ++i) out.head_joint_offset_std[layout.head[i]] = std::sqrt(std::max(0.0, h(i, i)));
    }
    return true;
  };
  // Pixel residuals of the current parameters (px), to estimate the noise.
  auto pixelResiduals = [&]() {
    std::vector<double> r;
    const double* p[4] = {x, m, arm.empty() ? head.data() : arm.data(), head.data()};
    for (const Use& u : uses) {
      const MarkerObservation& o = u.right ? u.sample->right : u.sample->left;
      DetectionResidual f{&model, &layout, u.right ? &cameras.right : &cameras.left, u.sample, u.right,
                          marker_points, o.points, start.fixed_point, start.marker_offset, 1.0, false, 0.0};
      std::vector<double> e(2 * marker_points.size());
      f(p, e.data());
      r.insert(r.end(), e.begin(), e.end());
    }
    return r;
  };

  // First with a nominal noise of 0.1 px, then once more with the noise the residuals show (the
  // Huber threshold and the priors' weight depend on it), and the covariance there.
  if (!solve(0.1, false)) return out;
  std::vector<double> r = pixelResiduals();
  std::vector<double> abs_r(r.size());
  std::transform(r.begin(), r.end(), abs_r.begin(), [](double v) { return std::abs(v); });
  const double sigma = std::max(0.005, 1.4826 * imagenets::frames::median(abs_r));
  if (!solve(sigma, true)) return out;
  r = pixelResiduals();
  double ss = 0;
  for (double v : r) ss += v * v;
  const int n_params = 12 + static_cast<int>(arm.size() + head.size());
  out.noise_sigma = sigma;
  out.reprojection_rms = std::sqrt(ss / r.size());
  out.observations = static_cast<int>(uses.size());
  // Honest scale: the covariance assumed noise `sigma`; if the residuals' variance (per degree of
  // freedom) is larger, the uncertainty is too.
  const double variance_factor = std::max(1.0, ss / std::max(1, static_cast<int>(r.size()) - n_params) / (sigma * sigma));
  out.fixed_point_covariance *= variance_factor;
  out.marker_offset_covariance *= variance_factor;
  for (double& s : out.arm_joint_offset_std) s *= std::sqrt(variance_factor);
  for (double& s : out.head_joint_offset_std) s *= std::sqrt(variance_factor);

  // The solution as frames.
  const Eigen::Isometry3d x_start = start.fixed_point, m_start = start.marker_offset;
  auto apply = [](const Eigen::Isometry3d& base, const double* p) {
    Eigen::Isometry3d t = base;
    const Eigen::Vector3d w(p[3], p[4], p[5]);
    if (w.norm() > 0) t.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * base.rotation();
    t.translation() = base.translation() + Eigen::Vector3d(p[0], p[1], p[2]);
    return t;
  };
  out.fixed_point = apply(x_start, x);
  out.marker_offset = apply(m_start, m);
  out.arm_joint_offsets = arm_full;
  out.head_joint_offsets = head_full;
  for (size_t i = 0; i < layout.arm.size(); ++i) out.arm_joint_offsets[layout.arm[i]] = arm[i];
  for (size_t i = 0; i < layout.head.size(); ++i) out.head_joint_offsets[layout.head[i]] = head[i];
  out.determined = 3 * std::sqrt(out.fixed_point_covariance.topLeftCorner<3, 3>().trace()) < prior_translation &&
                   out.fixed_point_covariance.trace() > 0;
  out.ok = true;
  char b[200];
  std::snprintf(b, sizeof b, "pixel-level bundle adjustment of %d detections: %.3f px RMS (noise %.3f px)", out.observations,
                out.reprojection_rms, sigma);
  if (out.message.empty()) out.message = b;
  else out.message = std::string(b) + "; " + out.message;
  return out;
}

}  // namespace friend_calibration
