#include <gtest/gtest.h>
#include <imagenets/FeedbackTrace.h>
#include <sensor_msgs/Image.h>

#include "imagenets/blocks/block_harness.h"

using namespace imagenets::blocks;

TEST(PlotFeedbackTrace, ImageOfTheRequestedSize) {
  imagenets::FeedbackTrace::Ptr t(new imagenets::FeedbackTrace);
  t->block = "threshold";
  t->property = "threshold";
  t->score = "detect.score";
  t->values = {1, 2, 3};
  t->scores = {0.1, 0.5, 0.2};
  t->found = true;
  t->chosen_value = 2;
  t->chosen_score = 0.5;
  BlockHarness h("imagenets/PlotFeedbackTrace");
  h.set("width", 320).set("height", 200).input("trace", t);
  h.run();
  auto img = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(img);
  EXPECT_EQ(img->encoding, "bgr8");
  EXPECT_EQ(img->width, 320u);
  EXPECT_EQ(img->height, 200u);
}

TEST(PlotFeedbackTrace, MismatchedTraceIsNamedError) {
  imagenets::FeedbackTrace::Ptr t(new imagenets::FeedbackTrace);
  t->values = {1, 2, 3};
  t->scores = {0.1};
  BlockHarness h("imagenets/PlotFeedbackTrace");
  h.input("trace", t);
  EXPECT_NE(h.runError().find("input 'trace': feedback trace of .: 3 values but 1 scores"), std::string::npos)
      << h.runError();
  EXPECT_FALSE(h.hasOutput("image"));
}
