// libapriltag as a peer detector on rendered AprilTags.
#include <gtest/gtest.h>

#include "imagenets/vision/apriltag_marker.h"

using namespace imagenets;

TEST(AprilTagDetector, FindsTheRenderedTagAtItsTruePoseWithDistortion) {
  render::CameraModel cam;
  cam.width = 1024;
  cam.height = 768;
  cam.K = cv::Matx33d(1400, 0, 515.2, 0, 1400, 381.6, 0, 0, 1);
  cam.D = {-0.25, 0.12, 0.0, 0.0, 0.0};
  const render::Renderer r(cam, 3);
  marker::AprilTagOptions options;
  options.id = 3;
  const marker::AprilTagDetector detector(options);
  for (double pan : {0.0, 100.0, 230.0}) {
    Eigen::Isometry3d truth = render::lookAtOriginPose(0.6, pan * M_PI / 180, 30 * M_PI / 180);
    truth.translation() += Eigen::Vector3d(0.12, 0.08, 0.0);
    render::Scene scene;
    scene.planes.push_back(marker::aprilTagPlane(options, 3, 0.25, truth));
    render::RenderOptions o;
    o.blur_sigma = 0.7;
    o.noise_sigma = 2.0;
    const marker::Detection d = detector.detect(r.render(scene, o), cam);
    ASSERT_TRUE(d.found) << "pan " << pan;
    EXPECT_LT(1000 * (d.pose.translation() - truth.translation()).norm(), 5.0) << "pan " << pan;
    EXPECT_LT(marker::rotationAngle(d.pose, truth) * 180 / M_PI, 2.0) << "pan " << pan;
  }
  options.id = 4;  // another id: not reported
  const marker::AprilTagDetector other(options);
  render::Scene scene;
  scene.planes.push_back(marker::aprilTagPlane(options, 3, 0.25, render::lookAtOriginPose(0.6, 0, 0)));
  EXPECT_FALSE(other.detect(r.render(scene), cam).found);
  EXPECT_THROW(marker::AprilTagOptions bad; bad.family = "tag99"; marker::AprilTagDetector x(bad), std::invalid_argument);
}
