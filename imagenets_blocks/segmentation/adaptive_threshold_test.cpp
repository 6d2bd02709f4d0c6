#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(AdaptiveThreshold, FindsDarkSpotsUnderAGradient) {
  // A left-to-right lighting ramp 20..220 with a dark spot (value - 40) on each side. A fixed
  // threshold cannot separate both spots from their surroundings; the local one can.
  cv::Mat in(40, 200, CV_8UC1);
  for (int c = 0; c < 200; ++c) in.col(c).setTo(20 + c);
  in(cv::Rect(20, 15, 6, 6)) -= 40;
  in(cv::Rect(170, 15, 6, 6)) -= 40;
  BlockHarness h("imagenets/AdaptiveThreshold");
  h.set("block_size", 15).set("offset", 10.0).set("invert", true);
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header()));
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  auto at = [&](int r, int c) { return out->data[r * out->step + c]; };
  EXPECT_EQ(at(17, 22), 255);   // dark spot in the dim part
  EXPECT_EQ(at(17, 172), 255);  // dark spot in the bright part
  EXPECT_EQ(at(5, 100), 0);     // plain ramp
  h.set("block_size", 16);
  EXPECT_NE(h.runError().find("property 'block_size': 16 is even"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("image"));
}
