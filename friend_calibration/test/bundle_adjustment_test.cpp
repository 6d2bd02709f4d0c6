// The pixel-level bundle adjustment and its uncertainty on simulated calibrations with known
// truth: random true robots (the simulator's own error drawing), the joint method's ten poses,
// the marker's 8 points projected through the true geometry and the description's camera models
// with pixel noise, each detection's pose fitted to its noisy points as the detector does.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <yaml-cpp/yaml.h>

#include "imagenets_calibration/bundle_adjustment.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets_calibration/storage.h"
#include "friend_hw_sim/true_robot.h"
#include "imagenets/package_file.h"

namespace imagenets_calibration {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Simulated {
  RobotModel truth;
  std::vector<Sample> samples;
};

struct BundleAdjustmentTest : ::testing::Test {
  RobotModel model{robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"))};
  StereoCameras cameras = *stereoCamerasOf(model.description(), nullptr);
  std::vector<Eigen::Vector3d> points = markerDefinedPoints(model.description().marker_size);

  static std::string trueErrorFile() {
    return imagenets::packageFile("friend_hw_sim", "config/true_error.yaml");
  }

  // One detection as the detector reports it: noisy distorted points, the pose fitted to them.
  MarkerObservation observe(const PinholeCamera& camera, const Eigen::Isometry3d& marker_in_camera, double noise_px,
                            std::mt19937& rng) const {
    std::normal_distribution<double> noise(0, noise_px);
    MarkerObservation o;
    o.found = true;
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (const auto& p : points) {
      const Eigen::Vector2d uv = camera.project(marker_in_camera * p) + Eigen::Vector2d(noise(rng), noise(rng));
      o.points.push_back(uv);
      object.emplace_back(p.x(), p.y(), p.z());
      image.emplace_back(uv.x(), uv.y());
    }
    cv::Mat k(3, 3, CV_64F);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) k.at<double>(r, c) = camera.K(r, c);
    }
    cv::Vec3d rvec, tvec;
    cv::solvePnP(object, image, k, cv::Mat(camera.distortion), rvec, tvec, false, cv::SOLVEPNP_IPPE);
    cv::Mat rot;
    cv::Rodrigues(rvec, rot);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) o.pose.linear()(r, c) = rot.at<double>(r, c);
      o.pose.translation()[r] = tvec[r];
    }
    double ss = 0;
    for (size_t i = 0; i < points.size(); ++i) ss += (camera.project(o.pose * points[i]) - o.points[i]).squaredNorm();
    o.reprojection_error = std::sqrt(ss / points.size());
    o.confidence = 1.0;
    return o;
  }

  // A random true robot (seed) seen from the joint method's poses. The encoder offsets of arm
  // joints 1 and n and of the pan are set to zero: no calibration of this kind can tell them from
  // the fixed point's and the marker's own rotation (calibration.h).
  Simulated simulate(int seed, double noise_px, int poses = 10) const {
    auto error = friend_hw_sim::loadTrueError(trueErrorFile(), model.description(), seed);
    error.arm_joint_offsets.front() = error.arm_joint_offsets.back() = 0;
    error.head_joint_offsets.front() = 0;
    return simulate(error, seed, noise_px, poses);
  }
  Simulated simulate(const friend_hw_sim::TrueRobotError& error, int seed, double noise_px, int poses = 10) const {
    Simulated s{RobotModel(friend_hw_sim::applyTrueError(model.description(), error)), {}};
    std::mt19937 rng(1000 + seed);
    for (const auto& pose : calibrationPoses(model, poses, "joint")) {
      Sample sample;
      sample.arm_q = pose.arm;
      sample.head_q = pose.head;
      const Eigen::Isometry3d marker = s.truth.marker(pose.arm);
      sample.left = observe(cameras.left, s.truth.leftCamera(pose.head).inverse() * marker, noise_px, rng);
      sample.right = observe(cameras.right, s.truth.rightCamera(pose.head).inverse() * marker, noise_px, rng);
      s.samples.push_back(sample);
    }
    return s;
  }
};

TEST_F(BundleAdjustmentTest, ProjectionMatchesTheRenderersCameraModel) {
  // PinholeCamera::project is the bundle adjustment's own (templated) projection: it must agree
  // with OpenCV's, which the renderer and the detector use.
  const Eigen::Vector3d p(0.12, -0.09, 0.55);
  std::vector<cv::Point2d> uv;
  cv::Mat k(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k.at<double>(r, c) = cameras.left.K(r, c);
  }
  cv::projectPoints(std::vector<cv::Point3d>{{p.x(), p.y(), p.z()}}, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k,
                    cv::Mat(cameras.left.distortion), uv);
  ASSERT_FALSE(cameras.left.distortion.empty());
  EXPECT_NEAR(cameras.left.project(p).x(), uv[0].x, 1e-9);
  EXPECT_NEAR(cameras.left.project(p).y(), uv[0].y, 1e-9);
}

TEST_F(BundleAdjustmentTest, TrueErrorLiesWithinTheReportedThreeSigmaAndIsNoWorseThanTheOldJointSolve) {
  const int robots = 12;
  int within = 0;
  std::vector<double> ratio_t, ratio_r;
  double sum_old = 0, sum_ba = 0;
  for (int seed = 1; seed <= robots; ++seed) {
    const Simulated sim = simulate(seed, 0.05);
    const Eigen::Isometry3d truth = sim.truth.headBase();
    const Result r = calibrate(model, sim.samples, "joint", FusionLimits(), CombineOptions());
    ASSERT_TRUE(r.success) << r.message;
    ASSERT_TRUE(r.has_covariance) << r.message;
    EXPECT_NE(r.message.find("pixel-level bundle adjustment of 20 detections"), std::string::npos) << r.message;
    // Today's joint solve (3D marker points from each detection's pose) on the same samples.
    const Result old = solveJointly(model, calibrate(model, sim.samples, "paper", FusionLimits(), CombineOptions()),
                                    FusionLimits());
    const double et = (r.fixed_point.translation() - truth.translation()).norm(), er = angleBetween(r.fixed_point, truth);
    const double old_t = (old.fixed_point.translation() - truth.translation()).norm();
    sum_old += old_t;
    sum_ba += et;
    const bool ok = et <= 3 * r.sigmaTranslation() && er <= 3 * r.sigmaRotation();
    within += ok;
    ratio_t.push_back(et / r.sigmaTranslation());
    ratio_r.push_back(er / r.sigmaRotation());
    std::printf("robot %2d: joint %.4f mm / %.5f deg; pixel-level %.4f mm / %.5f deg, 3 sigma %.4f mm / %.5f deg %s\n", seed,
                old_t * 1000, angleBetween(old.fixed_point, truth) / kDeg, et * 1000, er / kDeg,
                3000 * r.sigmaTranslation(), 3 * r.sigmaRotation() / kDeg, ok ? "" : "OUTSIDE");
  }
  std::sort(ratio_t.begin(), ratio_t.end());
  std::sort(ratio_r.begin(), ratio_r.end());
  std::printf("within 3 sigma: %d of %d; median error / sigma: translation %.2f, rotation %.2f\n", within, robots,
              ratio_t[robots / 2], ratio_r[robots / 2]);
  EXPECT_GE(within, robots - 1);
  // Honest both ways: the bound is not a wide net that any error falls into.
  EXPECT_GT(ratio_t[robots / 2], 0.2);
  EXPECT_GT(ratio_r[robots / 2], 0.2);
  EXPECT_LE(sum_ba, sum_old);
}

// A second robot that exists only as a URDF (config/six_axis: 6 joints, other link lengths, its
// own pan-tilt head and marker place), read with KDL (robot_description/urdf_kinematics.h): the
// same calibration (poses, joint method, pixel-level fit) finds its fixed point within the
// targets and within its reported 3 sigma.
TEST_F(BundleAdjustmentTest, ASixJointRobotThatExistsOnlyAsAUrdfIsCalibratedToo) {
  model = RobotModel(robot_description::loadRobotDescription(imagenets::packageFile("robot_description", "config/six_axis/robot.yaml")));
  ASSERT_EQ(model.description().arm.joints.size(), 6u);
  cameras = *stereoCamerasOf(model.description(), nullptr);
  points = markerDefinedPoints(model.description().marker_size);
  friend_hw_sim::TrueRobotError error;  // as config/friend/true_error.yaml's explicit values
  error.head_mount_xyz = {0.009, -0.008, 0.009};
  error.head_mount_rpy = Eigen::Vector3d(1.0, -1.2, 1.2) * kDeg;
  error.marker_xyz = {0.0008, -0.0005, 0.0};
  error.marker_rpy = Eigen::Vector3d(0.3, -0.2, 0.0) * kDeg;
  error.arm_joint_offsets = {0, -0.08 * kDeg, 0.04 * kDeg, 0.06 * kDeg, -0.05 * kDeg, 0};
  error.head_joint_offsets = {0, -0.08 * kDeg};
  const Simulated sim = simulate(error, 1, 0.05);
  const Eigen::Isometry3d truth = sim.truth.headBase();
  const Result r = calibrate(model, sim.samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_GE(r.used.size(), 8u) << r.message;
  EXPECT_NE(r.message.find("pixel-level bundle adjustment of"), std::string::npos) << r.message;
  const double et = (r.fixed_point.translation() - truth.translation()).norm(), er = angleBetween(r.fixed_point, truth);
  std::printf("six_axis: %.4f mm / %.5f deg off the true fixed point, 3 sigma %.4f mm / %.5f deg\n", et * 1000, er / kDeg,
              3000 * r.sigmaTranslation(), 3 * r.sigmaRotation() / kDeg);
  EXPECT_LT(et, 0.0005);
  EXPECT_LT(er, 0.05 * kDeg);
  EXPECT_LE(et, 3 * r.sigmaTranslation());
  EXPECT_LE(er, 3 * r.sigmaRotation());
  // The nominal fixed point it started from was 15 mm / 2 deg off.
  EXPECT_GT((model.headBase().translation() - truth.translation()).norm(), 0.014);
}

TEST_F(BundleAdjustmentTest, DetectionsWhosePointsDoNotFitTheCameraModelAreNotUsed) {
  Simulated sim = simulate(1, 0.05);
  for (auto& s : sim.samples) {
    for (auto* o : {&s.left, &s.right}) {
      for (auto& p : o->points) p += Eigen::Vector2d(4, 0);  // another camera's principal point
    }
  }
  const Result r = calibrate(model, sim.samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_FALSE(r.has_covariance);
  EXPECT_NE(r.message.find("pixel-level fit skipped: 0 detections with points that fit the camera model (20 do not)"),
            std::string::npos)
      << r.message;
}

TEST_F(BundleAdjustmentTest, TheUncertaintyTravelsThroughTheFileAndTheMessageAndOldFilesStillLoad) {
  const Result r = calibrate(model, simulate(2, 0.05).samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r.has_covariance) << r.message;
  EXPECT_GT(r.reprojection_rms, 0.0);
  EXPECT_GT(r.arm_joint_offset_std[1], 0.0);
  EXPECT_EQ(r.arm_joint_offset_std[0], 0.0);  // not estimated
  const auto dir = std::filesystem::temp_directory_path() / ("bundle_adjustment_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  StoredCalibration stored;
  stored.result = r;
  ASSERT_EQ(saveCalibration(stored, (dir / "new.yaml").string()), "");
  const Result loaded = loadCalibration((dir / "new.yaml").string()).result;
  EXPECT_TRUE(loaded.has_covariance);
  EXPECT_LT((loaded.fixed_point_covariance - r.fixed_point_covariance).norm(), 1e-12 * r.fixed_point_covariance.norm());
  EXPECT_LT((loaded.marker_offset_covariance - r.marker_offset_covariance).norm(), 1e-12 * r.marker_offset_covariance.norm());
  EXPECT_EQ(loaded.head_joint_offset_std, r.head_joint_offset_std);
  const Result via_msg = fromMsg(toMsg(r, "base_link", "pth_fixed_point"));
  EXPECT_TRUE(via_msg.has_covariance);
  EXPECT_EQ(via_msg.fixed_point_covariance, r.fixed_point_covariance);
  EXPECT_EQ(via_msg.arm_joint_offset_std, r.arm_joint_offset_std);
  // The observability report too.
  EXPECT_GT(r.condition_number, 1.0);
  EXPECT_EQ(loaded.condition_number, r.condition_number);
  EXPECT_EQ(loaded.unobservable, r.unobservable);
  EXPECT_EQ(via_msg.condition_number, r.condition_number);
  EXPECT_EQ(via_msg.unobservable, r.unobservable);
  // A file written before the pixel-level fit (no covariance keys) loads without one.
  stored.result.has_covariance = false;
  ASSERT_EQ(saveCalibration(stored, (dir / "old.yaml").string()), "");
  const Result old = loadCalibration((dir / "old.yaml").string()).result;
  EXPECT_FALSE(old.has_covariance);
  EXPECT_EQ(old.fixed_point_covariance, (Eigen::Matrix<double, 6, 6>::Zero()));
  EXPECT_EQ(old.condition_number, 0.0);
  EXPECT_TRUE(old.unobservable.empty());
  std::filesystem::remove_all(dir);
}

TEST_F(BundleAdjustmentTest, OneLoopOfTwoPosesIsReportedAsLeavingTheMarkersRotationAndTheFixedPointUnobservable) {
  // One relative motion leaves the marker offset's rotation about that motion's axis free, and
  // with it the fixed point: the result says which parameters the poses did not determine.
  const Result r = calibrate(model, simulate(2, 0.05, 2).samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r.has_covariance) << r.message;
  auto named = [&](const std::string& prefix) {
    return std::any_of(r.unobservable.begin(), r.unobservable.end(),
                       [&](const std::string& n) { return n.rfind(prefix, 0) == 0; });
  };
  EXPECT_TRUE(named("marker offset r")) << r.message;
  EXPECT_TRUE(named("fixed point ")) << r.message;
  EXPECT_NE(r.message.find("not observable from these poses (posterior std > 0.5 x prior): fixed point"),
            std::string::npos)
      << r.message;
  // Ten poses determine everything.
  const Result ten = calibrate(model, simulate(2, 0.05).samples, "joint", FusionLimits(), CombineOptions());
  EXPECT_TRUE(ten.unobservable.empty()) << ten.message;
  EXPECT_NE(ten.message.find("every estimated parameter observable"), std::string::npos) << ten.message;
  // An infinite condition number survives the file.
  Result inf = r;
  inf.condition_number = std::numeric_limits<double>::infinity();
  const auto dir = std::filesystem::temp_directory_path() / ("unobservable_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  StoredCalibration stored;
  stored.result = inf;
  ASSERT_EQ(saveCalibration(stored, (dir / "c.yaml").string()), "");
  const Result loaded = loadCalibration((dir / "c.yaml").string()).result;
  EXPECT_TRUE(std::isinf(loaded.condition_number));
  EXPECT_EQ(loaded.unobservable, r.unobservable);
  std::filesystem::remove_all(dir);
}

// The joint method's fallback (refineAtPixelLevel): the pixel-level fit replaces the 3D-point
// solution only when it determines the fixed point (3 sigma below the 30 mm prior); else the
// 3D-point solution stays, with the fit's honest (large) uncertainty. Both branches through
// calibrate(), each checked against the two solutions computed apart on the same samples.
struct OneLoopFallback {
  Result calibrated, point;  // calibrate()'s result; the 3D-point joint solution alone
  BundleAdjustment ba;       // the pixel-level fit started from it
};

OneLoopFallback solveBothWays(const BundleAdjustmentTest& t, const std::vector<Sample>& samples) {
  FusionLimits limits;
  limits.relative_reprojection_error = 0;  // no tightening: every step sees the same limits
  OneLoopFallback f;
  f.calibrated = calibrate(t.model, samples, "joint", limits, CombineOptions());
  f.point = solveJointly(t.model, calibrate(t.model, samples, "paper", limits, CombineOptions()), limits);
  std::vector<const Sample*> used;
  for (int i : f.point.used) used.push_back(&f.point.samples[i]);
  f.ba = bundleAdjust(t.model, CameraModels(t.model.description(), t.cameras), t.points, used, f.point, limits.max_reprojection_error);
  return f;
}

TEST_F(BundleAdjustmentTest, OneLoopKeepsThe3DPointSolutionWhenThePixelLevelFitLeavesTheFixedPointUndetermined) {
  const OneLoopFallback f = solveBothWays(*this, simulate(3, 0.05, 2).samples);  // one loop: 2 poses
  ASSERT_TRUE(f.calibrated.success) << f.calibrated.message;
  ASSERT_TRUE(f.ba.ok) << f.ba.message;
  EXPECT_FALSE(f.ba.determined) << "3 sigma " << 3000 * std::sqrt(f.ba.fixed_point_covariance.topLeftCorner<3, 3>().trace())
                                << " mm";
  // The fit did move the fixed point, so keeping the 3D-point solution is a choice, seen here.
  const double moved = (f.ba.fixed_point.translation() - f.point.fixed_point.translation()).norm();
  std::printf("one loop: pixel-level fit %.3f mm / %.4f deg from the 3D-point solution; 3 sigma %.1f mm\n", moved * 1000,
              angleBetween(f.ba.fixed_point, f.point.fixed_point) / kDeg, 3000 * f.calibrated.sigmaTranslation());
  EXPECT_GT(moved, 1e-6);
  EXPECT_NEAR((f.calibrated.fixed_point.translation() - f.point.fixed_point.translation()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(angleBetween(f.calibrated.fixed_point, f.point.fixed_point), 0.0, 1e-12);
  EXPECT_NEAR((f.calibrated.marker_offset.translation() - f.point.marker_offset.translation()).norm(), 0.0, 1e-12);
  EXPECT_EQ(f.calibrated.arm_joint_offsets, f.point.arm_joint_offsets);
  // ... with the fit's uncertainty, which says how little one loop knows.
  ASSERT_TRUE(f.calibrated.has_covariance);
  EXPECT_GE(3 * f.calibrated.sigmaTranslation(), 0.03);
  EXPECT_NE(f.calibrated.message.find("the images do not determine the fixed point (too few different poses): the "
                                      "3D-point solution is kept"),
            std::string::npos)
      << f.calibrated.message;
}

TEST_F(BundleAdjustmentTest, TenPosesUseThePixelLevelFitBecauseItDeterminesTheFixedPoint) {
  const OneLoopFallback f = solveBothWays(*this, simulate(3, 0.05, 10).samples);
  ASSERT_TRUE(f.calibrated.success) << f.calibrated.message;
  ASSERT_TRUE(f.ba.ok) << f.ba.message;
  EXPECT_TRUE(f.ba.determined);
  EXPECT_GT((f.ba.fixed_point.translation() - f.point.fixed_point.translation()).norm(), 1e-6);
  // (The same fit run twice: equal up to the solver's floating-point summation order.)
  EXPECT_NEAR((f.calibrated.fixed_point.translation() - f.ba.fixed_point.translation()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(angleBetween(f.calibrated.fixed_point, f.ba.fixed_point), 0.0, 1e-9);
  EXPECT_NEAR((f.calibrated.marker_offset.translation() - f.ba.marker_offset.translation()).norm(), 0.0, 1e-9);
  ASSERT_EQ(f.calibrated.arm_joint_offsets.size(), f.ba.arm_joint_offsets.size());
  for (size_t j = 0; j < f.ba.arm_joint_offsets.size(); ++j) {
    EXPECT_NEAR(f.calibrated.arm_joint_offsets[j], f.ba.arm_joint_offsets[j], 1e-9) << "arm joint " << j + 1;
  }
  EXPECT_LT(3 * f.calibrated.sigmaTranslation(), 0.03);
  EXPECT_EQ(f.calibrated.message.find("3D-point solution is kept"), std::string::npos) << f.calibrated.message;
}

TEST_F(BundleAdjustmentTest, AGoodCalibrationIsNotOverwrittenByOneWithAnUncertaintyAboveTheLimit) {
  const Result good = calibrate(model, simulate(3, 0.05).samples, "joint", FusionLimits(), CombineOptions());
  // Ten times the pixel noise (the detection gates opened to let it through).
  FusionLimits loose;
  loose.max_reprojection_error = 5;
  loose.relative_reprojection_error = 0;
  loose.max_position_difference = 0.05;
  loose.max_angle_difference = 0.2;
  const Result noisy = calibrate(model, simulate(3, 0.5).samples, "joint", loose, CombineOptions());
  ASSERT_TRUE(good.has_covariance) << good.message;
  ASSERT_TRUE(noisy.has_covariance) << noisy.message;
  ASSERT_LT(3 * good.sigmaTranslation(), 0.002);
  ASSERT_GT(3 * noisy.sigmaTranslation(), 0.003);
  const auto dir = std::filesystem::temp_directory_path() / ("overwrite_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "pth_fixed_point.yaml").string();
  EXPECT_EQ(overwriteRefusal(noisy, file, 0.002), "");  // nothing saved yet
  StoredCalibration stored;
  stored.result = good;
  saveCalibration(stored, file);
  const std::string refusal = overwriteRefusal(noisy, file, 0.002);
  EXPECT_NE(refusal.find("calibration not saved: its uncertainty (3 sigma)"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("above ~max_uncertainty 2.000 mm"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find(file), std::string::npos) << refusal;
  EXPECT_EQ(overwriteRefusal(good, file, 0.002), "");
  EXPECT_EQ(overwriteRefusal(noisy, file, 0.0), "");  // off
  std::filesystem::remove_all(dir);
}

// Each estimated parameter's standard deviation is the root of its own diagonal element of the
// fit's posterior covariance (found by the parameter's name), in the result, in the file (written
// and read back) and in the Calibrate response.
TEST_F(BundleAdjustmentTest, EachEstimatedParameterHasItsStandardDeviationInTheFileAndTheResponse) {
  const OneLoopFallback f = solveBothWays(*this, simulate(4, 0.05, 10).samples);
  ASSERT_TRUE(f.ba.ok && f.ba.determined) << f.ba.message;
  const Observability& o = f.ba.observability;
  auto posterior = [&](const std::string& name) {
    for (size_t i = 0; i < o.parameters.size(); ++i) {
      if (o.parameters[i].name == name) return std::sqrt(o.covariance(i, i));
    }
    ADD_FAILURE() << "the fit has no parameter '" << name << "'";
    return -1.0;
  };
  const char* axes[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(f.ba.fixedPointStd()[i], posterior(std::string("fixed point ") + axes[i]));
    EXPECT_DOUBLE_EQ(f.ba.markerOffsetStd()[i], posterior(std::string("marker offset ") + axes[i]));
    EXPECT_GT(f.ba.fixedPointStd()[i], 0.0);
  }
  const auto& arm = model.description().arm.joints;
  const auto& head = model.description().head.joints;
  for (size_t j = 1; j + 1 < arm.size(); ++j) EXPECT_DOUBLE_EQ(f.ba.arm_joint_offset_std[j], posterior(arm[j].name + " offset"));
  EXPECT_DOUBLE_EQ(f.ba.head_joint_offset_std[1], posterior(head[1].name + " offset"));
  EXPECT_EQ(f.ba.arm_joint_offset_std.front(), 0.0);  // not estimated
  EXPECT_EQ(f.ba.head_joint_offset_std.front(), 0.0);
  std::printf("1 sigma: fixed point x y z %.4f %.4f %.4f mm, rx ry rz %.5f %.5f %.5f deg; %s offset %.5f deg\n",
              1000 * f.ba.fixedPointStd()[0], 1000 * f.ba.fixedPointStd()[1], 1000 * f.ba.fixedPointStd()[2],
              f.ba.fixedPointStd()[3] / kDeg, f.ba.fixedPointStd()[4] / kDeg, f.ba.fixedPointStd()[5] / kDeg,
              arm[1].name.c_str(), f.ba.arm_joint_offset_std[1] / kDeg);
  // calibrate() ran the same fit (equal up to the solver's summation order).
  const Result& r = f.calibrated;
  EXPECT_LT((r.fixedPointStd() - f.ba.fixedPointStd()).norm(), 1e-6 * f.ba.fixedPointStd().norm());

  const auto dir = std::filesystem::temp_directory_path() / ("std_dev_" + std::to_string(::getpid()));
  StoredCalibration stored;
  stored.result = r;
  ASSERT_EQ(saveCalibration(stored, (dir / "c.yaml").string()), "");
  const YAML::Node file = YAML::LoadFile((dir / "c.yaml").string());
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(file["fixed_point_std_dev"]["xyz"][i].as<double>(), r.fixedPointStd()[i]);
    EXPECT_DOUBLE_EQ(file["fixed_point_std_dev"]["rotation"][i].as<double>(), r.fixedPointStd()[3 + i]);
    EXPECT_DOUBLE_EQ(file["marker_offset_std_dev"]["xyz"][i].as<double>(), r.markerOffsetStd()[i]);
    EXPECT_DOUBLE_EQ(file["marker_offset_std_dev"]["rotation"][i].as<double>(), r.markerOffsetStd()[3 + i]);
  }
  EXPECT_EQ(file["arm_joint_offset_std"].as<std::vector<double>>(), r.arm_joint_offset_std);
  const Result loaded = loadCalibration((dir / "c.yaml").string()).result;
  EXPECT_EQ(loaded.fixedPointStd(), r.fixedPointStd());
  EXPECT_EQ(loaded.markerOffsetStd(), r.markerOffsetStd());
  EXPECT_EQ(loaded.arm_joint_offset_std, r.arm_joint_offset_std);
  EXPECT_EQ(loaded.head_joint_offset_std, r.head_joint_offset_std);
  std::filesystem::remove_all(dir);

  imagenets_calibration_msgs::Calibrate::Response response;
  summarize(toMsg(r, "base_link", "pth_fixed_point"), response);
  for (int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(response.fixed_point_std_dev[i], r.fixedPointStd()[i]);
    EXPECT_DOUBLE_EQ(response.marker_offset_std_dev[i], r.markerOffsetStd()[i]);
  }
  EXPECT_EQ(response.arm_joint_offset_std, r.arm_joint_offset_std);
  EXPECT_EQ(response.head_joint_offset_std, r.head_joint_offset_std);
}

// free_params: a parameter held keeps its nominal value exactly (and has no uncertainty); the
// others still converge to the truth.
TEST_F(BundleAdjustmentTest, HeldParametersKeepTheirNominalValueAndTheOthersConverge) {
  auto error = friend_hw_sim::loadTrueError(trueErrorFile(), model.description(), 5);
  error.arm_joint_offsets.front() = error.arm_joint_offsets.back() = 0;
  error.head_joint_offsets.front() = 0;
  // (a) The target where it is drawn and arm joint 3 reading true: both held.
  error.marker_xyz.setZero();
  error.marker_rpy.setZero();
  error.arm_joint_offsets[2] = 0;
  auto d = model.description();
  d.free_params = {"fixed_point"};
  for (size_t j = 1; j + 1 < d.arm.joints.size(); ++j) {
    if (j != 2) d.free_params.push_back(d.arm.joints[j].name);
  }
  d.free_params.push_back(d.head.joints[1].name);
  const RobotModel held(d);
  const Simulated sim = simulate(error, 5, 0.05);
  const Result r = calibrate(held, sim.samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r.success && r.has_covariance) << r.message;
  EXPECT_EQ(r.marker_offset.matrix(), d.marker.pose.matrix());
  EXPECT_EQ(r.arm_joint_offsets[2], 0.0);
  EXPECT_EQ(r.markerOffsetStd(), (Eigen::Matrix<double, 6, 1>::Zero()));
  EXPECT_EQ(r.arm_joint_offset_std[2], 0.0);
  EXPECT_GT(r.arm_joint_offset_std[1], 0.0);
  const Eigen::Isometry3d truth = sim.truth.headBase();
  const double et = (r.fixed_point.translation() - truth.translation()).norm(), er = angleBetween(r.fixed_point, truth);
  // The joint offsets: from none (nominal) to within a small part of the largest true one.
  double worst_joint = 0, largest_true = 0;
  for (size_t j = 0; j < error.arm_joint_offsets.size(); ++j) {
    worst_joint = std::max(worst_joint, std::abs(r.arm_joint_offsets[j] - error.arm_joint_offsets[j]));
    largest_true = std::max(largest_true, std::abs(error.arm_joint_offsets[j]));
  }
  std::printf("target offset and %s held: fixed point %.4f mm / %.5f deg off the truth (3 sigma %.4f mm); joint "
              "offsets within %.5f deg (largest true %.5f deg)\n",
              d.arm.joints[2].name.c_str(), et * 1000, er / kDeg, 3000 * r.sigmaTranslation(), worst_joint / kDeg,
              largest_true / kDeg);
  EXPECT_LT(et, 0.0005);
  EXPECT_LT(er, 0.05 * kDeg);
  EXPECT_LE(et, 3 * r.sigmaTranslation());
  EXPECT_LT(worst_joint, 0.03 * kDeg);
  EXPECT_LT(worst_joint, 0.5 * largest_true);

  // (b) The head mount where it is drawn, held: exactly nominal; the target offset still found.
  auto mount_true = error;
  mount_true.head_mount_xyz.setZero();
  mount_true.head_mount_rpy.setZero();
  mount_true.marker_xyz = {0.0008, -0.0005, 0.0};
  mount_true.marker_rpy = Eigen::Vector3d(0.3, -0.2, 0.0) * kDeg;
  d.free_params = {"target_offset", "joint_offsets"};
  const RobotModel mount_held(d);
  const Simulated sim2 = simulate(mount_true, 6, 0.05);
  const Result r2 = calibrate(mount_held, sim2.samples, "joint", FusionLimits(), CombineOptions());
  ASSERT_TRUE(r2.success && r2.has_covariance) << r2.message;
  EXPECT_EQ(r2.fixed_point.matrix(), d.head.mount.matrix());
  EXPECT_EQ(r2.fixedPointStd(), (Eigen::Matrix<double, 6, 1>::Zero()));
  const Eigen::Isometry3d marker_truth = sim2.truth.description().marker.pose;
  const double mt = (r2.marker_offset.translation() - marker_truth.translation()).norm();
  std::printf("head mount held: target offset %.4f mm / %.5f deg off the truth\n", mt * 1000,
              angleBetween(r2.marker_offset, marker_truth) / kDeg);
  EXPECT_LT(mt, 0.0005);
  EXPECT_LT(angleBetween(r2.marker_offset, marker_truth), 0.05 * kDeg);
}

}  // namespace
}  // namespace imagenets_calibration
