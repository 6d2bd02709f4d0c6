// A reduced marker study (24 views: 12 per lighting) that guards the accuracy targets.
#include <gtest/gtest.h>

#include "marker_study/marker_study.h"

using namespace imagenets::marker;

TEST(MarkerStudy, ReducedStudyMeetsTheAccuracyTargets) {
  StudyConfig config;
  config.pan_from = 15;
  config.pan_to = 285;
  config.pan_step = 90;  // 4 pans
  config.tilt_from = 0;
  config.tilt_to = 70;
  config.tilt_step = 35;  // 3 tilts, up to the steepest
  config.supersampling = 3;
  config.threads = 2;
  int last = 0;
  const auto rows = runStudy(config, [&](int done, int total) {
    EXPECT_EQ(total, 24);
    last = done;
  });
  EXPECT_EQ(last, 24);
  ASSERT_EQ(rows.size(), 24u * 3);
  const auto summary = summarize(rows);
  ASSERT_EQ(summary.size(), 6u);  // 3 methods x 2 lightings
  for (const auto& lighting : {"even", "varying"}) {
    const StudySummaryRow* feedback = nullptr;
    const StudySummaryRow* april = nullptr;
    for (const auto& s : summary) {
      if (s.lighting != lighting) continue;
      if (s.method == "feedback") feedback = &s;
      if (s.method == "apriltag") april = &s;
    }
    ASSERT_TRUE(feedback && april) << lighting;
    EXPECT_EQ(feedback->found, feedback->images) << lighting;
    EXPECT_LE(feedback->max_mm, 3.0) << lighting;
    EXPECT_LE(feedback->median_mm, 0.5) << lighting;
    EXPECT_LE(feedback->median_mm, april->median_mm) << lighting;  // no worse than the peer
    EXPECT_LE(feedback->median_deg, 0.5) << lighting;
  }
  const std::string csv = toCsv(rows);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 72);
  const cv::Mat map = errorMapImage(rows, "even", 3.0);
  EXPECT_FALSE(map.empty());
}
