// The launch files of launch/nets/ produce their outputs (launch_nets.test starts them).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

namespace {

sensor_msgs::ImageConstPtr firstImage(const std::string& topic) {
  return ros::topic::waitForMessage<sensor_msgs::Image>(topic, ros::Duration(15.0));
}

bool isBinary(const sensor_msgs::Image& image) {
  for (uint8_t v : image.data) {
    if (v != 0 && v != 255) return false;
  }
  return true;
}

TEST(LaunchNets, Fig3_3ChainThresholdsTheImage) {
  auto binary = firstImage("/segmentation/threshold/out/image");
  ASSERT_TRUE(binary) << "no image from the Fig. 3.3 chain";
  EXPECT_EQ(binary->encoding, "mono8");
  EXPECT_TRUE(isBinary(*binary));
}

TEST(LaunchNets, Fig3_4SubNetsProcessBothCameras) {
  auto left = firstImage("/stereo/left_segmentation/out/binary");
  auto right = firstImage("/stereo/right_segmentation/out/binary");
  ASSERT_TRUE(left) << "nothing from the left sub-net";
  ASSERT_TRUE(right) << "nothing from the right sub-net";
  // Each instance processed its own camera's images (the header travels through the sub-net).
  EXPECT_EQ(left->header.frame_id, "stereo_left_optical_frame");
  EXPECT_EQ(right->header.frame_id, "stereo_right_optical_frame");
  EXPECT_TRUE(isBinary(*left));
  EXPECT_EQ(left->data, right->data);  // the same file on both sides, the same sub-net
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "launch_nets_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
