// OpenCV's hand-eye methods set up for the eye-to-hand case give the true camera and target
// offset from exact samples: the set-up (which pose goes where) is right.
#include <gtest/gtest.h>

#include <random>

#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/hand_eye_peers.h"

using namespace imagenets_calibration;

namespace {

Eigen::Isometry3d frame(double x, double y, double z, double rx, double ry, double rz) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

}  // namespace

TEST(HandEyePeers, EveryMethodFindsTheTruthFromExactEyeToHandSamples) {
  const Eigen::Isometry3d base_camera = frame(0.1, -0.2, 1.2, 2.4, 0.1, -0.3);
  const Eigen::Isometry3d tcp_target = frame(0.01, 0.02, 0.08, 0.2, -0.1, 0.3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<HandEyeSample> samples;
  for (int i = 0; i < 10; ++i) {
    HandEyeSample s;
    s.base_tcp = frame(0.2 + 0.1 * u(rng), 0.1 * u(rng), 0.5 + 0.1 * u(rng), 0.4 * u(rng), 0.4 * u(rng), 0.6 * u(rng));
    s.camera_target = base_camera.inverse() * s.base_tcp * tcp_target;
    samples.push_back(s);
  }
  const auto solutions = eyeToHandPeers(samples);
  ASSERT_EQ(solutions.size(), 7u);
  for (const auto& s : solutions) {
    ASSERT_TRUE(s.ok) << s.method << ": " << s.error;
    EXPECT_LT((s.base_camera.translation() - base_camera.translation()).norm(), 1e-6) << s.method;
    EXPECT_LT(angleBetween(s.base_camera, base_camera), 1e-6) << s.method;
    EXPECT_LT((s.tcp_target.translation() - tcp_target.translation()).norm(), 1e-6) << s.method;
    EXPECT_LT(angleBetween(s.tcp_target, tcp_target), 1e-6) << s.method;
  }
  EXPECT_EQ(solutions.front().method, "Tsai");
  EXPECT_EQ(solutions.back().method, "Li");
}
