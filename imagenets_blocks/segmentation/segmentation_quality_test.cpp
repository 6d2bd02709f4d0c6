#include <gtest/gtest.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/executor.h"

using namespace imagenets;

namespace {
// gray: left half 50, right half 200; threshold it at `t` and score the result.
std::unique_ptr<Executor> scoreAt(int t) {
  auto e = std::make_unique<Executor>(Net::build(parseNetText(R"(
blocks:
  threshold: {type: imagenets/Threshold}
  quality: {type: imagenets/SegmentationQuality}
links: [threshold.image -> quality.binary]
)", "q.yaml", "")));
  cv::Mat gray(10, 20, CV_8UC1, cv::Scalar(50));
  gray.colRange(10, 20).setTo(200);
  auto msg = blocks::toImageMsg(gray, "mono8", std_msgs::Header());
  e->setInput<sensor_msgs::Image>("threshold.image", msg);
  e->setInput<sensor_msgs::Image>("quality.gray", msg);
  e->setProperty("threshold", "threshold", t);
  e->run();
  return e;
}
}  // namespace

TEST(SegmentationQuality, PerfectSplitScoresOne) {
  EXPECT_NEAR(scoreAt(100)->output<std_msgs::Float64>("quality.score")->data, 1.0, 1e-12);
}

TEST(SegmentationQuality, NoSplitScoresZero) {
  EXPECT_NEAR(scoreAt(250)->output<std_msgs::Float64>("quality.score")->data, 0.0, 1e-12);
  EXPECT_NEAR(scoreAt(0)->output<std_msgs::Float64>("quality.score")->data, 0.0, 1e-12);
}

TEST(SegmentationQuality, MismatchedSizesAreANamedError) {
  auto e = std::make_unique<Executor>(Net::build(parseNetText(
      "blocks:\n  quality: {type: imagenets/SegmentationQuality}\n", "q.yaml", "")));
  e->setInput<sensor_msgs::Image>("quality.gray", blocks::toImageMsg(cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)), "mono8", {}));
  e->setInput<sensor_msgs::Image>("quality.binary", blocks::toImageMsg(cv::Mat(5, 4, CV_8UC1, cv::Scalar(1)), "mono8", {}));
  RunReport r = e->run();
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_NE(r.failed[0].find("block 'quality' (imagenets/SegmentationQuality): inputs 'gray' (4x4) and 'binary' (4x5) differ in size"),
            std::string::npos)
      << r.failed[0];
}
