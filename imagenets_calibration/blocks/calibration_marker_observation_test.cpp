#include <gtest/gtest.h>
#include <imagenets/FeedbackTrace.h>
#include <imagenets/MarkerDetection.h>
#include <imagenets_calibration_msgs/MarkerObservation.h>
#include <std_msgs/String.h>

#include "imagenets/blocks/block_harness.h"

using imagenets::blocks::BlockHarness;

TEST(CalibrationMarkerObservation, FoundCarriesPoseScoreThresholdAndPoints) {
  auto detection = boost::make_shared<imagenets::MarkerDetection>();
  detection->found = true;
  detection->confidence = 0.93;
  detection->reprojection_error = 0.02;
  detection->pose.position.z = 0.6;
  detection->pose.orientation.w = 1;
  detection->points.resize(8);
  detection->points[3].x = 512.25;
  auto trace = boost::make_shared<imagenets::FeedbackTrace>();
  trace->chosen_value = 97;
  BlockHarness h("imagenets/CalibrationMarkerObservation");
  h.input("detection", detection).input("feedback_trace", trace);
  h.run();
  const auto o = h.output<imagenets_calibration_msgs::MarkerObservation>("observation");
  ASSERT_TRUE(o);
  EXPECT_TRUE(o->found);
  EXPECT_EQ(o->threshold, 97);
  EXPECT_EQ(o->confidence, 0.93);
  EXPECT_EQ(o->reprojection_error, 0.02);
  EXPECT_EQ(o->pose.position.z, 0.6);
  ASSERT_EQ(o->points.size(), 8u);
  EXPECT_EQ(o->points[3].x, 512.25);
}

TEST(CalibrationMarkerObservation, NotFoundSaysWhyFromTheSubNetsFailure) {
  auto failure = boost::make_shared<std_msgs::String>();
  failure->data = "block 'threshold': feedback: no valid candidate";
  BlockHarness h("imagenets/CalibrationMarkerObservation");
  h.input("failure", failure);
  h.run();
  const auto o = h.output<imagenets_calibration_msgs::MarkerObservation>("observation");
  EXPECT_FALSE(o->found);
  EXPECT_EQ(o->reason, failure->data);
  EXPECT_EQ(o->pose.orientation.w, 1.0);  // a valid (identity) pose, never an all-zero quaternion
}
