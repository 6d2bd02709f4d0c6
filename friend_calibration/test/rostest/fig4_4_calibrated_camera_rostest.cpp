// rostest: the Fig. 4.4 launch net (launch/nets/fig4_4_calibrated_camera.launch) with the simulated
// robot and the calibration node. After one calibration:
//  - the extrinsics the net outputs (imagenets/LookupTransform) equal the calibrated fixed point
//    (from the service response) times the nominal head chain at the pan/tilt of joint_states,
//    computed here without TF;
//  - the stereo point cloud (Debian's stereo_image_proc) is in the calibrated camera frame, and its
//    points, moved to base_link with that extrinsic matrix, lie on the table of config/friend/scene.yaml;
//  - the node has published the detection images (bgr8, marker outline drawn) with camera_info.
#include <algorithm>
#include <cmath>
#include <mutex>

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/storage.h"
#include "friend_hw_sim/cameras.h"
#include "robot_description/joint_state.h"
#include "robot_description/robot_model.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets/vision/frames.h"
#include "imagenets/testing/rostest_util.h"
#include "imagenets/package_file.h"

namespace {

const std::string kCalibratedLeft = "calibrated/stereo_left_optical_frame";

}  // namespace

TEST(Fig4_4CalibratedCamera, ExtrinsicsCloudAndDetectionImages) {
  ros::NodeHandle nh;
  LatestMessage<sensor_msgs::Image> detection_left("/friend_calibration/detections/left/image");
  LatestMessage<sensor_msgs::Image> detection_right("/friend_calibration/detections/right/image");
  LatestMessage<sensor_msgs::CameraInfo> detection_left_info("/friend_calibration/detections/left/camera_info");
  LatestMessage<geometry_msgs::TransformStamped> extrinsics("/fig4_4/left/extrinsics");
  LatestMessage<sensor_msgs::CameraInfo> calibrated_info("/fig4_4/left/camera_info");
  LatestMessage<sensor_msgs::PointCloud2> cloud("/fig4_4/points2");
  LatestMessage<sensor_msgs::JointState> joints("/joint_states");

  ASSERT_TRUE(ros::service::waitForService("/friend_calibration/calibrate", ros::Duration(30)));
  imagenets_calibration_msgs::Calibrate srv;
  srv.request.redundancy = 3;
  ASSERT_TRUE(ros::service::call("/friend_calibration/calibrate", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const ros::Time calibrated = ros::Time::now();
  EXPECT_EQ(srv.response.fixed_point.header.frame_id, "base_link");
  const Eigen::Isometry3d fixed_point =
      imagenets::frames::toIsometry(srv.response.fixed_point.transform, "response fixed_point");

  // Detection images of the last sample (latched): bgr8, full size, the outline drawn in red
  // on the grey camera image (so a red pixel can only come from the drawing).
  for (auto* topic : {&detection_left, &detection_right}) {
    auto img = topic->wait(5.0);
    ASSERT_TRUE(img) << "no detection image";
    EXPECT_EQ(img->encoding, "bgr8");
    EXPECT_EQ(img->width, 1024u);
    EXPECT_EQ(img->height, 768u);
    ASSERT_EQ(img->step, img->width * 3);
    size_t red = 0;
    for (size_t i = 0; i + 2 < img->data.size(); i += 3) {
      if (img->data[i + 2] > 200 && img->data[i] < 60 && img->data[i + 1] < 60) ++red;
    }
    EXPECT_GT(red, 200u) << "no marker outline drawn";
  }
  auto info = detection_left_info.wait(5.0);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->header.stamp, detection_left.wait(0.0)->header.stamp);  // the model of that very image
  EXPECT_GT(info->K[0], 0.0);

  // The extrinsics of an image taken after the calibration, and independently: the calibrated
  // fixed point (service response) * the calibrated head chain at the head's current angles (the head
  // rests after the calibration, so joint_states now are the angles at that image).
  auto ext = extrinsics.waitFrom(calibrated + ros::Duration(0.3), 20.0);
  ASSERT_TRUE(ext) << "no /fig4_4/left/extrinsics after the calibration";
  EXPECT_EQ(ext->header.frame_id, "base_link");
  EXPECT_EQ(ext->child_frame_id, kCalibratedLeft);
  auto model_info = calibrated_info.waitFrom(ext->header.stamp, 5.0);
  ASSERT_TRUE(model_info);
  EXPECT_EQ(model_info->header.frame_id, kCalibratedLeft);
  auto js = joints.waitFrom(ext->header.stamp, 5.0);
  ASSERT_TRUE(js);
  const robot_description::RobotModel model(robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml")));
  const std::vector<double> head = robot_description::jointPositions(*js, model.description().head.names());
  // The head chain as calibrated: with the estimated zero offsets (the tilt's) of the saved file.
  const robot_description::RobotModel calibrated_model =
      imagenets_calibration::calibratedModel(model, imagenets_calibration::loadCalibration(srv.response.file).result);
  const Eigen::Isometry3d expected = fixed_point * imagenets_calibration::headChain(calibrated_model, head);
  const Eigen::Isometry3d got = imagenets::frames::toIsometry(ext->transform, "extrinsics");
  EXPECT_LT((got.translation() - expected.translation()).norm(), 1e-4)
      << "got " << got.translation().transpose() << ", expected " << expected.translation().transpose();
  EXPECT_LT(Eigen::AngleAxisd(got.rotation().transpose() * expected.rotation()).angle(), 1e-4);
  // And it is not the nominal camera (the true head is mounted ~15 mm / 2 deg off the drawing).
  const Eigen::Isometry3d nominal = model.headBase() * imagenets_calibration::headChain(model, head);
  EXPECT_GT((got.translation() - nominal.translation()).norm(), 0.003);

  // The stereo point cloud: in the calibrated camera frame; on the table where the table is.
  auto pc = cloud.waitFrom(ext->header.stamp, 20.0);
  ASSERT_TRUE(pc) << "no /fig4_4/points2 after the calibration";
  EXPECT_EQ(pc->header.frame_id, kCalibratedLeft);
  const auto scene = friend_hw_sim::loadWorldScene(imagenets::packageFile("friend_hw_sim", "config/scene.yaml"));
  const friend_hw_sim::WorldPlane* table = nullptr;
  std::vector<const friend_hw_sim::WorldPlane*> boxes;
  for (const auto& p : scene.planes) {
    if (p.name == "table") table = &p;
    else if (p.name != "floor" && p.name != "wall") boxes.push_back(&p);
  }
  ASSERT_TRUE(table);
  ASSERT_FALSE(boxes.empty());
  const Eigen::Isometry3d cloud_to_table = table->pose.inverse() * expected;
  std::vector<double> heights;  // above the table top, m
  size_t valid = 0;
  for (sensor_msgs::PointCloud2ConstIterator<float> it(*pc, "x"); it != it.end(); ++it) {
    if (!std::isfinite(it[0]) || !std::isfinite(it[2])) continue;
    ++valid;
    const Eigen::Vector3d p(it[0], it[1], it[2]);
    const Eigen::Vector3d in_base = expected * p;
    const Eigen::Vector3d on_table = cloud_to_table * p;
    // Inside the table top with a margin, away from the boxes' faces, not the arm above it.
    if (std::abs(on_table.x()) > table->width / 2 - 0.05 || std::abs(on_table.y()) > table->height / 2 - 0.05) continue;
    if (std::abs(on_table.z()) > 0.1) continue;
    bool near_box = false;
    for (const auto* b : boxes) {
      const Eigen::Vector3d c = b->pose.translation();
      near_box |= std::hypot(in_base.x() - c.x(), in_base.y() - c.y()) < std::max(b->width, b->height) + 0.04;
    }
    if (!near_box) heights.push_back(on_table.z());
  }
  ASSERT_GT(valid, 20000u) << "the cloud is almost empty";
  ASSERT_GT(heights.size(), 2000u) << "too few cloud points over the table (" << heights.size() << ")";
  std::sort(heights.begin(), heights.end());
  const double median = heights[heights.size() / 2];
  const auto close = std::count_if(heights.begin(), heights.end(), [](double h) { return std::abs(h) < 0.015; });
  EXPECT_LT(std::abs(median), 0.006) << "the table seen by the calibrated camera is " << median * 1000 << " mm off";
  EXPECT_GT(static_cast<double>(close) / heights.size(), 0.8);
  // For comparison (printed, not asserted): the same points placed with the nominal camera.
  std::vector<double> nominal_heights;
  for (sensor_msgs::PointCloud2ConstIterator<float> it(*pc, "x"); it != it.end(); ++it) {
    if (!std::isfinite(it[0]) || !std::isfinite(it[2])) continue;
    const Eigen::Vector3d on_table = table->pose.inverse() * nominal * Eigen::Vector3d(it[0], it[1], it[2]);
    if (std::abs(on_table.x()) < table->width / 2 - 0.05 && std::abs(on_table.y()) < table->height / 2 - 0.05 &&
        std::abs(on_table.z()) < 0.1) {
      nominal_heights.push_back(on_table.z());
    }
  }
  std::sort(nominal_heights.begin(), nominal_heights.end());
  if (!nominal_heights.empty()) {
    std::printf("nominal camera would put the table %.2f mm off\n", nominal_heights[nominal_heights.size() / 2] * 1000);
  }
  std::printf("cloud: %zu valid points, %zu over the table, median height %.2f mm, %.0f%% within 15 mm\n", valid,
              heights.size(), median * 1000, 100.0 * close / heights.size());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "fig4_4_calibrated_camera_rostest");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
