#include <boost/make_shared.hpp>
#include <gtest/gtest.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "imagenets/blocks/block_harness.h"

using imagenets::blocks::BlockHarness;

namespace {

sensor_msgs::ImagePtr image(unsigned w, unsigned h, double stamp) {
  auto m = boost::make_shared<sensor_msgs::Image>();
  m->header.frame_id = "stereo_left_optical_frame";
  m->header.stamp = ros::Time(stamp);
  m->width = w;
  m->height = h;
  m->encoding = "mono8";
  m->step = w;
  m->data.assign(w * h, 0);
  for (unsigned i = 0; i < m->data.size(); ++i) m->data[i] = static_cast<uint8_t>(i * 7);
  return m;
}

sensor_msgs::CameraInfoPtr info(unsigned w, unsigned h, double stamp) {
  auto m = boost::make_shared<sensor_msgs::CameraInfo>();
  m->header.frame_id = "stereo_left_optical_frame";
  m->header.stamp = ros::Time(stamp);
  m->width = w;
  m->height = h;
  m->K = {500, 0, 8, 0, 500, 6, 0, 0, 1};
  m->D = {0.1, -0.2, 0, 0, 0};
  return m;
}

}  // namespace

TEST(SetCameraFrame, RelabelsBothMessagesAndKeepsEverythingElse) {
  BlockHarness h("imagenets/SetCameraFrame");
  auto in = image(16, 12, 5.5);
  auto model = info(16, 12, 5.5);
  h.set("frame_id", std::string("calibrated/stereo_left_optical_frame")).input("image", in).input("camera_info", model);
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  auto out_info = h.output<sensor_msgs::CameraInfo>("camera_info");
  ASSERT_TRUE(out && out_info);
  EXPECT_EQ(out->header.frame_id, "calibrated/stereo_left_optical_frame");
  EXPECT_EQ(out_info->header.frame_id, "calibrated/stereo_left_optical_frame");
  EXPECT_EQ(out->header.stamp, in->header.stamp);
  EXPECT_EQ(out_info->header.stamp, in->header.stamp);
  EXPECT_EQ(out->data, in->data);
  EXPECT_EQ(out->encoding, "mono8");
  EXPECT_EQ(out_info->K, model->K);
  EXPECT_EQ(out_info->D, model->D);
  // The inputs are untouched (messages are shared between blocks).
  EXPECT_EQ(in->header.frame_id, "stereo_left_optical_frame");
  EXPECT_EQ(model->header.frame_id, "stereo_left_optical_frame");
}

TEST(SetCameraFrame, MismatchedPairsAndBadFramesAreNamed) {
  BlockHarness h("imagenets/SetCameraFrame");
  h.input("image", image(16, 12, 5.5)).input("camera_info", info(16, 12, 6.0));
  EXPECT_NE(h.runError().find("stamp"), std::string::npos);
  h.input("camera_info", info(32, 12, 5.5));
  EXPECT_NE(h.runError().find("32x12"), std::string::npos);
  auto binned = info(32, 24, 5.5);  // a decimated image: camera_info keeps the sensor size
  binned->binning_x = binned->binning_y = 2;
  h.input("camera_info", binned);
  EXPECT_EQ(h.runError(), "");
  h.input("camera_info", info(16, 12, 5.5)).set("frame_id", std::string(""));
  EXPECT_NE(h.runError().find("property 'frame_id'"), std::string::npos);
  h.set("frame_id", std::string("a frame"));
  EXPECT_NE(h.runError().find("white space"), std::string::npos);
  h.clear("camera_info").set("frame_id", std::string("x"));
  EXPECT_NE(h.runError().find("input 'camera_info'"), std::string::npos);
}
