// A reduced marker study (--quick: 12 views per condition) that guards the accuracy targets: the
// paper's two conditions, and the harder ones against libapriltag.
#include <gtest/gtest.h>

#include <algorithm>

#include "marker_study/marker_study.h"

using namespace imagenets::marker;

namespace {

const StudySummaryRow& summaryOf(const std::vector<StudySummaryRow>& summary, const std::string& condition,
                                 const std::string& method) {
  for (const auto& s : summary) {
    if (s.condition == condition && s.method == method) return s;
  }
  throw std::runtime_error("no summary row " + condition + " / " + method);
}

}  // namespace

TEST(MarkerStudy, ReducedStudyMeetsTheAccuracyTargets) {
  StudyConfig config;
  makeQuick(&config);
  config.threads = 2;
  int last = 0;
  const auto rows = runStudy(config, [&](int done, int total) {
    EXPECT_EQ(total, 24);
    last = done;
  });
  EXPECT_EQ(last, 24);
  ASSERT_EQ(rows.size(), 24u * 6);  // fixed40, detect, calibration, apriltag, apriltag_target, charuco
  const auto summary = summarize(rows);
  ASSERT_EQ(summary.size(), 12u);  // 6 methods x 2 conditions
  for (const auto& condition : {"even", "varying"}) {
    for (const auto& method : {"detect", "calibration"}) {
      const StudySummaryRow& ours = summaryOf(summary, condition, method);
      const StudySummaryRow& april = summaryOf(summary, condition, "apriltag");
      EXPECT_EQ(ours.found, ours.images) << condition << " " << method;
      EXPECT_LE(ours.max_mm, 3.0) << condition << " " << method;
      EXPECT_LE(ours.median_mm, 0.5) << condition << " " << method;
      EXPECT_LE(ours.median_mm, april.median_mm) << condition << " " << method;  // no worse than the peer
      EXPECT_LE(ours.median_deg, 0.5) << condition << " " << method;
    }
  }
  const std::string csv = toCsv(rows);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 144);
  const auto back = fromCsv(csv);
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_EQ(back[5].condition, rows[5].condition);
  EXPECT_NEAR(back[5].illumination, rows[5].illumination, 1e-3);
  const cv::Mat map = errorMapImage(rows, "even", 3.0);
  EXPECT_FALSE(map.empty());
}

TEST(MarkerStudy, HarderConditionsMeetTheTargetsAgainstAprilTag) {
  StudyConfig config;
  makeQuick(&config);
  config.conditions = selectConditions("hard");
  config.threads = 2;
  const auto rows = runStudy(config);
  ASSERT_EQ(rows.size(), config.conditions.size() * 12 * 6);
  // The views really are drawn within each condition's ranges.
  for (const auto& r : rows) {
    const StudyCondition& c = selectConditions(r.condition).front();
    EXPECT_GE(r.distance, c.distance_min - 1e-9) << r.condition;
    EXPECT_LE(r.distance, c.distance_max + 1e-9) << r.condition;
    EXPECT_GE(r.illumination, c.illumination_min - 1e-9) << r.condition;
    EXPECT_LE(r.illumination, c.illumination_max + 1e-9) << r.condition;
    EXPECT_LE(r.blur, c.blur_max + 1e-9) << r.condition;
    EXPECT_LE(r.noise, c.noise_max + 1e-9) << r.condition;
  }
  const auto summary = summarize(rows);
  const auto checks = checkTargets(summary);
  ASSERT_EQ(checks.size(), config.conditions.size() * 2);  // detect and calibration
  for (const auto& t : checks) {
    const StudySummaryRow& ours = summaryOf(summary, t.condition, t.method);
    const StudySummaryRow& april = summaryOf(summary, t.condition, "apriltag");
    const std::string what = t.condition + " " + t.method + ": found " + std::to_string(ours.found) + "/" +
                             std::to_string(ours.images) + " vs " + std::to_string(april.found) + ", median " +
                             std::to_string(ours.median_mm) + " vs " + std::to_string(april.median_mm) + " mm";
    EXPECT_TRUE(t.median_ok) << what;
    EXPECT_TRUE(t.rate_ok) << what;
  }
  const std::string table = sideBySideMarkdown(summary);
  EXPECT_NE(table.find("| combined |"), std::string::npos) << table;
}

// The worst imaging at once (1.5 m, 1.5 px blur, noise 5, 25 % light, dark wall) on 12 views up to
// 70 deg tilt: the default detection finds at least as many markers as libapriltag's own pipeline,
// and none of them farther off than libapriltag's worst.
TEST(MarkerStudy, InTheWorstImagingTheDefaultDetectionIsNoWorseThanAprilTagsWorst) {
  StudyConfig config;
  makeQuick(&config);
  config.conditions = selectConditions("worst");
  config.calibration_net.clear();
  config.tag_target.clear();
  config.board_target.clear();
  config.threads = 2;
  const auto summary = summarize(runStudy(config));
  const StudySummaryRow& ours = summaryOf(summary, "worst", "detect");
  const StudySummaryRow& april = summaryOf(summary, "worst", "apriltag");
  ASSERT_EQ(ours.images, 12);
  EXPECT_GE(ours.found, april.found);
  EXPECT_LE(ours.max_mm, april.max_mm) << "ours " << ours.max_mm << " mm, libapriltag " << april.max_mm << " mm";
  EXPECT_LE(ours.median_mm, 0.5 * april.median_mm);
}

// A lamp's glare on the print in every view: the square marker's nets and the printed targets
// run there too, and the nets find the marker at least as often as libapriltag finds its tag.
TEST(MarkerStudy, ReflectionsGiveRowsForEveryMethod) {
  StudyConfig config;
  makeQuick(&config);
  config.conditions = selectConditions("reflections");
  config.threads = 2;
  const auto rows = runStudy(config);
  ASSERT_EQ(rows.size(), 12u * 6);
  const auto summary = summarize(rows);
  const StudySummaryRow& april = summaryOf(summary, "reflections", "apriltag");
  for (const auto& method : {"detect", "calibration"}) {
    EXPECT_GE(summaryOf(summary, "reflections", method).found, april.found) << method;
  }
  for (const auto& method : {"apriltag_target", "charuco"}) EXPECT_EQ(summaryOf(summary, "reflections", method).images, 12);
  EXPECT_NE(toMarkdown(summary, config).find("a specular highlight near the marker"), std::string::npos);
}

TEST(MarkerStudy, UnknownConditionNamesTheNameAndTheKnownOnes) {
  try {
    selectConditions("even,foggy");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'foggy'"), std::string::npos) << what;
    EXPECT_NE(what.find("dim_dark_wall"), std::string::npos) << what;
  }
  EXPECT_EQ(selectConditions("paper").size(), 2u);
  EXPECT_EQ(selectConditions("all").size(), studyConditions().size());
  EXPECT_EQ(selectConditions("hard").size() + 3, studyConditions().size());  // not the paper's, not reflections
  EXPECT_EQ(selectConditions("dim,dim").size(), 1u);
}


TEST(MarkerStudy, DecoysCountAsFalsePositivesNotAsViews) {
  StudyConfig config;
  makeQuick(&config);
  config.conditions = selectConditions("combined");
  config.threads = 2;
  config.decoys = true;
  const auto rows = runStudy(config);
  ASSERT_EQ(rows.size(), 12u * 6 * 2);  // every method on the view and on its decoy
  EXPECT_EQ(std::count_if(rows.begin(), rows.end(), [](const StudyRow& r) { return r.decoy; }), 12 * 6);
  const auto summary = summarize(rows);
  for (const auto& method : {"detect", "calibration", "apriltag", "apriltag_target", "charuco"}) {
    const StudySummaryRow& s = summaryOf(summary, "combined", method);
    EXPECT_EQ(s.images, 12) << method;
    EXPECT_EQ(s.decoys, 12) << method;
    // Another pattern (another tag id) in the marker's place is not the marker.
    EXPECT_EQ(s.false_positives, 0) << method;
  }
  // The decoy flag survives the CSV; a CSV written before the column reads as views of the marker.
  const auto back = fromCsv(toCsv(rows));
  ASSERT_EQ(back.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(back[i].decoy, rows[i].decoy) << i;
  const auto old = fromCsv(
      "pan_deg,tilt_deg,condition,distance_m,blur_px,noise,illumination,background,method,found,position_error_mm,"
      "orientation_error_deg,threshold,time_ms\n"
      "0,0,even,0.600,0.700,2.000,1.000,0.500,detect,1,0.0331,0.0166,78,19.50\n"
      "0,0,even,0.600,0.700,2.000,1.000,0.500,apriltag,0,,,,\n");
  ASSERT_EQ(old.size(), 2u);
  EXPECT_FALSE(old[0].decoy);
  EXPECT_TRUE(old[0].found);
  EXPECT_FALSE(old[1].found);
  const std::string table = sideBySideMarkdown(summary);
  EXPECT_NE(table.find("false positives on decoys"), std::string::npos) << table;
  EXPECT_NE(table.find("0/12 / 0/12"), std::string::npos) << table;
}
