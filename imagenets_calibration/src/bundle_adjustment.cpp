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

using robot_description::FreeParams;

// The estimated parameters in the fit's order, named for the observability report: the fixed
// point's and the marker offset's translation and rotation (about the parent frame's axes), then
// the joint offsets by joint name.
// Parameters held at their nominal value (FreeParams) are not among them.
std::vector<std::string> parameterNames(const RobotModel& m, const FreeParams& layout) {
  std::vector<std::string> names;
  const std::pair<const char*, bool> frames[] = {{"fixed point ", layout.fixed_point}, {"marker offset ", layout.target_offset}};
  for (const auto& [frame, free] : frames) {
    if (!free) continue;
    for (const char* axis : {"x", "y", "z", "rx", "ry", "rz"}) names.push_back(std::string(frame) + axis);
  }
  for (size_t j : layout.arm) names.push_back(m.description().arm.joints[j].name + " offset");
  for (size_t j : layout.head) names.push_back(m.description().head.joints[j].name + " offset");
  return names;
}
// What is known before the fit: the marker offset and the joint offsets their priors; the fixed
// point (no prior in the fit) is judged against the same mounting tolerance as the marker.
std::vector<double> priorStd(const FreeParams& layout, double translation, double rotation, double offset) {
  std::vector<double> p;
  for (bool free : {layout.fixed_point, layout.target_offset}) {
    for (int i = 0; free && i < 6; ++i) p.push_back(i < 3 ? translation : rotation);
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
  const FreeParams* layout;
  const CalibrationCamera* camera;
  const Sample* sample;
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
    camera_in_base = camera_in_base * matrixOf(camera->in_head).cast<T>() * matrixOf(camera->in_rig).cast<T>();
    const Mat4<T> marker_in_camera = inverseOf(camera_in_base) * tcp * perturbed(m0, p[1]);
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Matrix<T, 3, 1> pc =
          marker_in_camera.template topLeftCorner<3, 3>() * points[i].cast<T>() + marker_in_camera.template topRightCorner<3, 1>();
      const Eigen::Matrix<T, 2, 1> uv = projectPoint(camera->model, pc);
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

CameraModels::CameraModels(const robot_description::RobotDescription& d, const StereoCameras& stereo) {
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  cameras = {{Sample::kLeft, stereo.left, d.image_width, d.image_height, d.left_camera.pose, identity},
             {Sample::kRight, stereo.right, d.image_width, d.image_height, d.left_camera.pose, RobotModel(d).leftToRight()}};
}

std::optional<CameraModels> cameraModelsOf(const robot_description::RobotDescription& d, std::string* why) {
  if (d.calibration_camera != "mono") {
    const auto stereo = stereoCamerasOf(d, why);
    if (!stereo) return std::nullopt;
    return CameraModels(d, *stereo);
  }
  try {
    const auto m = imagenets::render::CameraModel::fromCameraInfo(imagenets::readCameraInfo(d.mono_camera_info));
    CameraModels c;
    c.cameras = {{Sample::kMono, fromCameraModel(m), m.width, m.height, d.mono_camera.pose, Eigen::Isometry3d::Identity()}};
    return c;
  } catch (const std::exception& e) {
    if (why) *why = e.what();
    return std::nullopt;
  }
}

std::vector<Eigen::Vector3d> markerDefinedPoints(double size, double border) {
  const double o = size / 2, i = size * (1 - 2 * border) / 2;
  return {{-o, o, 0}, {o, o, 0}, {o, -o, 0}, {-o, -o, 0}, {-i, i, 0}, {i, i, 0}, {i, -i, 0}, {-i, -i, 0}};
}

namespace {

// One detection the fit uses: a sample's observation by one of the cameras.
struct Use {
  const Sample* sample;
  const CalibrationCamera* camera;
  const MarkerObservation& observation() const { return sample->observation(camera->observation); }
};

// The detections to fit: usable (as the chain uses them) and with points that fit their pose
// through the camera model; `mismatched` counts those that do not.
std::vector<Use> detectionsToFit(const CameraModels& cameras, const std::vector<Eigen::Vector3d>& marker_points,
                                 const std::vector<const Sample*>& samples, double max_reprojection_error,
                                 const BundleAdjustmentOptions& options, int& mismatched) {
  std::vector<Use> uses;
  for (const Sample* s : samples) {
    for (const CalibrationCamera& camera : cameras.cameras) {
      const Use u{s, &camera};
      const MarkerObservation& o = u.observation();
      const std::vector<Eigen::Vector3d>& points = o.object_points.empty() ? marker_points : o.object_points;
      if (!o.found || o.reprojection_error > max_reprojection_error || o.points.size() != points.size() || points.size() < 4) {
        continue;
      }
      if (rmsMismatch(camera.model, o, points) > options.max_point_mismatch) {
        ++mismatched;
        continue;
      }
      uses.push_back(u);
    }
  }
  return uses;
}

// The fit itself: its parameters are perturbations of `start` (fixed point, marker offset) and the
// free joint offsets; those held (FreeParams) stay at the start, which is their nominal value.
class PixelFit {
 public:
  static constexpr double kPriorTranslation = 0.03, kPriorRotation = 0.175, kPriorOffset = 0.0035;  // as solveJointly

  // (Each detection to fit names its camera, whose models outlive the fit.)
  PixelFit(const RobotModel& model, const std::vector<Eigen::Vector3d>& marker_points,
           std::vector<Use> uses, const Result& start, const BundleAdjustmentOptions& options)
      : model_(model), marker_points_(marker_points), uses_(std::move(uses)), start_(start),
        options_(options), layout_(robot_description::freeParams(model.description())) {
    const auto& d = model.description();
    arm_full_ = start.arm_joint_offsets;
    head_full_ = start.head_joint_offsets;
    arm_full_.resize(d.arm.joints.size(), 0.0);
    head_full_.resize(d.head.joints.size(), 0.0);
    for (size_t j : layout_.arm) arm_.push_back(arm_full_[j]);
    for (size_t j : layout_.head) head_.push_back(head_full_[j]);
  }

  // Solves with point noise `sigma` (px); with the covariance, keeps the whitened Jacobian at the
  // solution. False with `why` when the solver gives no usable solution.
  bool solve(double sigma, bool with_covariance, std::string& why) {
    ceres::Problem problem;
    std::vector<ceres::ResidualBlockId> data_ids, prior_ids;
    std::vector<double*> blocks{x_, m_};
    if (!arm_.empty()) blocks.push_back(arm_.data());
    if (!head_.empty()) blocks.push_back(head_.data());
    for (const Use& u : uses_) data_ids.push_back(problem.AddResidualBlock(detectionCost(u, sigma), nullptr, blocks));
    addPriors(problem, prior_ids);
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = options_.max_iterations;
    so.function_tolerance = 1e-12;
    so.parameter_tolerance = 1e-12;
    so.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      why = "pixel-level fit failed: " + summary.message;
      return false;
    }
    if (with_covariance) keepJacobian(problem, blocks, data_ids, prior_ids);
    return true;
  }

  // Pixel residuals of the current parameters (px), to estimate the noise.
  std::vector<double> pixelResiduals() const {
    std::vector<double> r;
    const double* p[4] = {x_, m_, arm_.empty() ? head_.data() : arm_.data(), head_.data()};
    for (const Use& u : uses_) {
      const DetectionResidual f = residualOf(u, 1.0, false);
      std::vector<double> e(2 * u.observation().points.size());
      f(p, e.data());
      r.insert(r.end(), e.begin(), e.end());
    }
    return r;
  }

  int parameterCount() const {
    return 6 * (layout_.fixed_point + layout_.target_offset) + static_cast<int>(arm_.size() + head_.size());
  }

  // Observability and uncertainty at the solution (`variance_factor`: see bundleAdjust), then the
  // solution as frames and full-length joint offsets.
  void takeResult(double variance_factor, BundleAdjustment& out) const {
    out.observability = analyseObservability(jacobian_, data_rows_, parameterNames(model_, layout_),
                                             priorStd(layout_, kPriorTranslation, kPriorRotation, kPriorOffset),
                                             variance_factor);
    takeUncertainty(out);
    auto apply = [](const Eigen::Isometry3d& base, const double* p) {
      Eigen::Isometry3d t = base;
      const Eigen::Vector3d w(p[3], p[4], p[5]);
      if (w.norm() > 0) t.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * base.rotation();
      t.translation() = base.translation() + Eigen::Vector3d(p[0], p[1], p[2]);
      return t;
    };
    out.fixed_point = apply(start_.fixed_point, x_);
    out.marker_offset = apply(start_.marker_offset, m_);
    out.arm_joint_offsets = arm_full_;
    out.head_joint_offsets = head_full_;
    for (size_t i = 0; i < layout_.arm.size(); ++i) out.arm_joint_offsets[layout_.arm[i]] = arm_[i];
    for (size_t i = 0; i < layout_.head.size(); ++i) out.head_joint_offsets[layout_.head[i]] = head_[i];
    // (A fixed point held at its nominal value needs no determining.)
    out.determined = !layout_.fixed_point || (3 * std::sqrt(out.fixed_point_covariance.topLeftCorner<3, 3>().trace()) <
                                                  kPriorTranslation &&
                                              out.fixed_point_covariance.trace() > 0);
  }

 private:
  DetectionResidual residualOf(const Use& u, double sigma, bool robust) const {
    const MarkerObservation& o = u.observation();
    return DetectionResidual{&model_, &layout_, u.camera, u.sample,
                             o.object_points.empty() ? marker_points_ : o.object_points, o.points, start_.fixed_point,
                             start_.marker_offset, sigma, robust, options_.huber_sigmas};
  }

  ceres::CostFunction* detectionCost(const Use& u, double sigma) const {
    // Stride 18: FRIEND's 18 parameters in one pass of dual numbers.
    auto* cost = new ceres::DynamicAutoDiffCostFunction<DetectionResidual, 18>(new DetectionResidual(residualOf(u, sigma, true)));
    cost->AddParameterBlock(6);
    cost->AddParameterBlock(6);
    if (!arm_.empty()) cost->AddParameterBlock(static_cast<int>(arm_.size()));
    if (!head_.empty()) cost->AddParameterBlock(static_cast<int>(head_.size()));
    cost->SetNumResiduals(static_cast<int>(2 * u.observation().points.size()));
    return cost;
  }

  // The held parameters constant; weak priors on the free marker offset and joint offsets.
  void addPriors(ceres::Problem& problem, std::vector<ceres::ResidualBlockId>& prior_ids) {
    if (!layout_.fixed_point) problem.SetParameterBlockConstant(x_);
    if (layout_.target_offset) {
      prior_ids.push_back(problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<MarkerPrior, 6, 6>(
              new MarkerPrior{start_.marker_offset, model_.description().marker.pose, kPriorTranslation, kPriorRotation}),
          nullptr, m_));
    } else {
      problem.SetParameterBlockConstant(m_);
    }
    for (auto* values : {&arm_, &head_}) {
      if (values->empty()) continue;
      auto* prior = new ceres::DynamicAutoDiffCostFunction<OffsetPrior, 8>(
          new OffsetPrior{static_cast<int>(values->size()), kPriorOffset});
      prior->AddParameterBlock(static_cast<int>(values->size()));
      prior->SetNumResiduals(static_cast<int>(values->size()));
      prior_ids.push_back(problem.AddResidualBlock(prior, nullptr, values->data()));
    }
  }

  // The whitened Jacobian at the solution over the free parameters (measurements first, then the
  // priors): the posterior covariance and which parameters the poses determine (observability.h).
  void keepJacobian(ceres::Problem& problem, std::vector<double*> blocks, const std::vector<ceres::ResidualBlockId>& data_ids,
                    const std::vector<ceres::ResidualBlockId>& prior_ids) {
    blocks.erase(std::remove_if(blocks.begin(), blocks.end(), [&](double* b) { return problem.IsParameterBlockConstant(b); }),
                 blocks.end());
    ceres::Problem::EvaluateOptions eo;
    eo.parameter_blocks = blocks;
    eo.residual_blocks = data_ids;
    eo.residual_blocks.insert(eo.residual_blocks.end(), prior_ids.begin(), prior_ids.end());
    ceres::CRSMatrix crs;
    problem.Evaluate(eo, nullptr, nullptr, nullptr, &crs);
    jacobian_ = denseOf(crs);
    data_rows_ = 0;
    for (const Use& u : uses_) data_rows_ += static_cast<int>(2 * u.observation().points.size());
  }

  // The posterior covariance (over the free parameters in the fit's order) as the Uncertainty of
  // every parameter: zero for those held at their nominal value.
  void takeUncertainty(BundleAdjustment& out) const {
    const auto& d = model_.description();
    const Eigen::MatrixXd& c = out.observability.covariance;
    out.unobservable = out.observability.unobservable;
    out.condition_number = out.observability.condition_number;
    out.has_covariance = out.observability.computed();
    Eigen::Index k = 0;
    if (layout_.fixed_point) {
      out.fixed_point_covariance = c.block<6, 6>(k, k);
      k += 6;
    }
    if (layout_.target_offset) {
      out.marker_offset_covariance = c.block<6, 6>(k, k);
      k += 6;
    }
    out.arm_joint_offset_std.assign(d.arm.joints.size(), 0.0);
    out.head_joint_offset_std.assign(d.head.joints.size(), 0.0);
    for (size_t j : layout_.arm) out.arm_joint_offset_std[j] = std::sqrt(c(k, k)), ++k;
    for (size_t j : layout_.head) out.head_joint_offset_std[j] = std::sqrt(c(k, k)), ++k;
  }

  const RobotModel& model_;
  const std::vector<Eigen::Vector3d>& marker_points_;
  const std::vector<Use> uses_;
  const Result& start_;
  const BundleAdjustmentOptions& options_;
  const FreeParams layout_;
  double x_[6] = {0, 0, 0, 0, 0, 0}, m_[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> arm_full_, head_full_, arm_, head_;
  Eigen::MatrixXd jacobian_;
  int data_rows_ = 0;
};

}  // namespace

BundleAdjustment bundleAdjust(const RobotModel& model, const CameraModels& cameras,
                              const std::vector<Eigen::Vector3d>& marker_points, const std::vector<const Sample*>& samples,
                              const Result& start, double max_reprojection_error, const BundleAdjustmentOptions& options) {
  BundleAdjustment out;
  int mismatched = 0;
  std::vector<Use> uses = detectionsToFit(cameras, marker_points, samples, max_reprojection_error, options, mismatched);
  if (uses.size() < 3) {
    out.message = "pixel-level fit skipped: " + std::to_string(uses.size()) + " detections with points that fit the camera model (" +
                  std::to_string(mismatched) + " do not)";
    return out;
  }
  out.observations = static_cast<int>(uses.size());
  PixelFit fit(model, marker_points, std::move(uses), start, options);
  // First with a nominal noise of 0.1 px, then once more with the noise the residuals show (the
  // Huber threshold and the priors' weight depend on it), and the covariance there.
  // (Or with the noise the options give, e.g. when predicting what poses will determine.)
  if (!fit.solve(options.noise_sigma > 0 ? options.noise_sigma : 0.1, false, out.message)) return out;
  std::vector<double> r = fit.pixelResiduals();
  std::vector<double> abs_r(r.size());
  std::transform(r.begin(), r.end(), abs_r.begin(), [](double v) { return std::abs(v); });
  const double sigma =
      options.noise_sigma > 0 ? options.noise_sigma : std::max(0.005, 1.4826 * imagenets::frames::median(abs_r));
  if (!fit.solve(sigma, true, out.message)) return out;
  r = fit.pixelResiduals();
  double ss = 0;
  for (double v : r) ss += v * v;
  out.noise_sigma = sigma;
  out.reprojection_rms = std::sqrt(ss / r.size());
  // Honest scale: the covariance assumed noise `sigma`; if the residuals' variance (per degree of
  // freedom) is larger, the uncertainty is too.
  const double variance_factor =
      std::max(1.0, ss / std::max(1, static_cast<int>(r.size()) - fit.parameterCount()) / (sigma * sigma));
  fit.takeResult(variance_factor, out);
  out.ok = true;
  char b[200];
  std::snprintf(b, sizeof b, "pixel-level bundle adjustment of %d detections: %.3f px RMS (noise %.3f px)", out.observations,
                out.reprojection_rms, sigma);
  out.message = b;
  return out;
}

}  // namespace imagenets_calibration

namespace imagenets_calibration {

Observability predictObservability(const RobotModel& model, const CameraModels& cameras,
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
    for (const CalibrationCamera& camera : cameras.cameras) {
      MarkerObservation& o = s.observation(camera.observation);
      o.pose = camera.pose(d.head.end(pose.head)).inverse() * marker;
      o.found = true;
      for (const auto& p : points) {
        const Eigen::Vector3d pc = o.pose * p;
        const Eigen::Vector2d uv = camera.model.project(pc);
        if (!(pc.z() > 0) || uv.x() < 0 || uv.y() < 0 || uv.x() > camera.width || uv.y() > camera.height) o.found = false;
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
