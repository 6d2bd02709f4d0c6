#include "imagenets_calibration/bundle_adjustment.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "imagenets/vision/frames.h"
#include "imagenets/vision/read_camera_info.h"
#include "imagenets/vision/render.h"

namespace imagenets_calibration {
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

// The estimated parameters in the fit's order, named for the observability report: the fixed
// point's and the marker offset's translation and rotation (about the parent frame's axes), then
// the joint offsets by joint name.
std::vector<std::string> parameterNames(const RobotModel& m, const OffsetLayout& layout) {
  std::vector<std::string> names;
  for (const char* frame : {"fixed point ", "marker offset "}) {
    for (const char* axis : {"x", "y", "z", "rx", "ry", "rz"}) names.push_back(std::string(frame) + axis);
  }
  for (size_t j : layout.arm) names.push_back(m.description().arm.joints[j].name + " offset");
  for (size_t j : layout.head) names.push_back(m.description().head.joints[j].name + " offset");
  return names;
}
// What is known before the fit: the marker offset and the joint offsets their priors; the fixed
// point (no prior in the fit) is judged against the same mounting tolerance as the marker.
std::vector<double> priorStd(const OffsetLayout& layout, double translation, double rotation, double offset) {
  std::vector<double> p;
  for (int frame = 0; frame < 2; ++frame) {
    for (int i = 0; i < 6; ++i) p.push_back(i < 3 ? translation : rotation);
  }
  p.resize(p.size() + layout.arm.size() + layout.head.size(), offset);
  return p;
}

Eigen::MatrixXd denseOf(const ceres::CRSMatrix& crs) {
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) j(r, crs.cols[k]) = crs.values[k];
  }
  return j;
}

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
  // A detection's points on the target: its own (a target's corners with ids), else the marker's.
  auto targetPoints = [&](const MarkerObservation& o) -> const std::vector<Eigen::Vector3d>& {
    return o.object_points.empty() ? marker_points : o.object_points;
  };
  for (const Sample* s : samples) {
    for (bool right : {false, true}) {
      const MarkerObservation& o = right ? s->right : s->left;
      const std::vector<Eigen::Vector3d>& points = targetPoints(o);
      if (!o.found || o.reprojection_error > max_reprojection_error || o.points.size() != points.size() || points.size() < 4) {
        continue;
      }
      if (rmsMismatch(right ? cameras.right : cameras.left, o, points) > options.max_point_mismatch) {
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
  Eigen::MatrixXd jacobian;
  int data_rows = 0;
  auto solve = [&](double sigma, bool with_covariance) {
    ceres::Problem problem;
    std::vector<ceres::ResidualBlockId> data_ids, prior_ids;
    std::vector<double*> blocks{x, m};
    if (!arm.empty()) blocks.push_back(arm.data());
    if (!head.empty()) blocks.push_back(head.data());
    for (const Use& u : uses) {
      const MarkerObservation& o = u.right ? u.sample->right : u.sample->left;
      auto* f = new DetectionResidual{&model, &layout, u.right ? &cameras.right : &cameras.left, u.sample, u.right,
                                      targetPoints(o), o.points, start.fixed_point, start.marker_offset, sigma, true,
                                      options.huber_sigmas};
      // Stride 18: FRIEND's 18 parameters in one pass of dual numbers.
      auto* cost = new ceres::DynamicAutoDiffCostFunction<DetectionResidual, 18>(f);
      cost->AddParameterBlock(6);
      cost->AddParameterBlock(6);
      if (!arm.empty()) cost->AddParameterBlock(static_cast<int>(arm.size()));
      if (!head.empty()) cost->AddParameterBlock(static_cast<int>(head.size()));
      cost->SetNumResiduals(static_cast<int>(2 * o.points.size()));
      data_ids.push_back(problem.AddResidualBlock(cost, nullptr, blocks));
    }
    prior_ids.push_back(problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<MarkerPrior, 6, 6>(
            new MarkerPrior{start.marker_offset, d.marker.pose, prior_translation, prior_rotation}),
        nullptr, m));
    for (auto* values : {&arm, &head}) {
      if (values->empty()) continue;
      auto* prior = new ceres::DynamicAutoDiffCostFunction<OffsetPrior, 8>(
          new OffsetPrior{static_cast<int>(values->size()), prior_offset});
      prior->AddParameterBlock(static_cast<int>(values->size()));
      prior->SetNumResiduals(static_cast<int>(values->size()));
      prior_ids.push_back(problem.AddResidualBlock(prior, nullptr, values->data()));
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
    // The whitened Jacobian at the solution (measurements first, then the priors): the posterior
    // covariance and which parameters the poses determine (observability.h).
    ceres::Problem::EvaluateOptions eo;
    eo.parameter_blocks = blocks;
    eo.residual_blocks = data_ids;
    eo.residual_blocks.insert(eo.residual_blocks.end(), prior_ids.begin(), prior_ids.end());
    ceres::CRSMatrix crs;
    problem.Evaluate(eo, nullptr, nullptr, nullptr, &crs);
    jacobian = denseOf(crs);
    data_rows = 0;
    for (const Use& u : uses) data_rows += static_cast<int>(2 * (u.right ? u.sample->right : u.sample->left).points.size());
    return true;
  };
  // Pixel residuals of the current parameters (px), to estimate the noise.
  auto pixelResiduals = [&]() {
    std::vector<double> r;
    const double* p[4] = {x, m, arm.empty() ? head.data() : arm.data(), head.data()};
    for (const Use& u : uses) {
      const MarkerObservation& o = u.right ? u.sample->right : u.sample->left;
      DetectionResidual f{&model, &layout, u.right ? &cameras.right : &cameras.left, u.sample, u.right,
                          targetPoints(o), o.points, start.fixed_point, start.marker_offset, 1.0, false, 0.0};
      std::vector<double> e(2 * o.points.size());
      f(p, e.data());
      r.insert(r.end(), e.begin(), e.end());
    }
    return r;
  };

  // First with a nominal noise of 0.1 px, then once more with the noise the residuals show (the
  // Huber threshold and the priors' weight depend on it), and the covariance there.
  // (Or with the noise the options give, e.g. when predicting what poses will determine.)
  if (!solve(options.noise_sigma > 0 ? options.noise_sigma : 0.1, false)) return out;
  std::vector<double> r = pixelResiduals();
  std::vector<double> abs_r(r.size());
  std::transform(r.begin(), r.end(), abs_r.begin(), [](double v) { return std::abs(v); });
  const double sigma =
      options.noise_sigma > 0 ? options.noise_sigma : std::max(0.005, 1.4826 * imagenets::frames::median(abs_r));
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
  out.observability = analyseObservability(jacobian, data_rows, parameterNames(model, layout),
                                           priorStd(layout, prior_translation, prior_rotation, prior_offset),
                                           variance_factor);
  const Eigen::MatrixXd& c = out.observability.covariance;
  out.unobservable = out.observability.unobservable;
  out.condition_number = out.observability.condition_number;
  out.fixed_point_covariance = c.block<6, 6>(0, 0);
  out.marker_offset_covariance = c.block<6, 6>(6, 6);
  out.arm_joint_offset_std.assign(d.arm.joints.size(), 0.0);
  out.head_joint_offset_std.assign(d.head.joints.size(), 0.0);
  for (size_t i = 0; i < layout.arm.size(); ++i) out.arm_joint_offset_std[layout.arm[i]] = std::sqrt(c(12 + i, 12 + i));
  for (size_t i = 0; i < layout.head.size(); ++i) {
    const size_t k = 12 + layout.arm.size() + i;
    out.head_joint_offset_std[layout.head[i]] = std::sqrt(c(k, k));
  }

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
  out.has_covariance = out.fixed_point_covariance.trace() > 0;
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

}  // namespace imagenets_calibration

namespace imagenets_calibration {

Observability predictObservability(const RobotModel& model, const StereoCameras& cameras,
                                   const std::vector<CalibrationPose>& poses, double noise_px) {
  const auto& d = model.description();
  const std::vector<Eigen::Vector3d> points = markerDefinedPoints(d.marker_size);
  // Each pose as the nominal robot would see it: exact points, those of a view that shows the
  // whole marker in front of the camera.
  std::vector<Sample> samples;
  for (const CalibrationPose& pose : poses) {
    Sample s;
    s.arm_q = pose.arm;
    s.head_q = pose.head;
    const Eigen::Isometry3d marker = model.marker(pose.arm);
    for (bool right : {false, true}) {
      const PinholeCamera& camera = right ? cameras.right : cameras.left;
      MarkerObservation& o = right ? s.right : s.left;
      o.pose = (right ? model.rightCamera(pose.head) : model.leftCamera(pose.head)).inverse() * marker;
      o.found = true;
      for (const auto& p : points) {
        const Eigen::Vector3d pc = o.pose * p;
        const Eigen::Vector2d uv = camera.project(pc);
        if (!(pc.z() > 0) || uv.x() < 0 || uv.y() < 0 || uv.x() > d.image_width || uv.y() > d.image_height) o.found = false;
        o.points.push_back(uv);
      }
      if (o.pose.linear().col(2).dot(o.pose.translation()) >= 0) o.found = false;  // its back to the camera
    }
    samples.push_back(std::move(s));
  }
  std::vector<const Sample*> use;
  for (const Sample& s : samples) use.push_back(&s);
  Result start;
  start.fixed_point = model.headBase();
  start.marker_offset = d.marker.pose;
  BundleAdjustmentOptions options;
  options.noise_sigma = noise_px;
  return bundleAdjust(model, cameras, points, use, start, std::numeric_limits<double>::infinity(), options).observability;
}

}  // namespace imagenets_calibration
