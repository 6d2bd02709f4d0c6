// The feedback search on its own (feedback_search.h): which candidates, in which order, when it
// stops. Scores come from plain functions here, no net.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "../src/feedback_search.h"

using namespace imagenets;

namespace {

FeedbackSpec range(double from, double to, double step, const std::string& search = "exhaustive") {
  FeedbackSpec f;
  f.from = from;
  f.to = to;
  f.step = step;
  for (double v = from; v <= to + 1e-9; v += step) f.values.push_back(v);
  f.search = search;
  return f;
}

// Runs the search to the end, one candidate at a time; returns the batches it asked for.
std::vector<std::vector<double>> drive(FeedbackSearch& search, const std::function<double(double)>& score) {
  std::vector<std::vector<double>> batches;
  for (auto batch = search.nextBatch(); !batch.empty(); batch = search.nextBatch()) {
    batches.push_back(batch);
    for (double v : batch) {
      if (!search.report(score(v))) break;
    }
  }
  return batches;
}

std::vector<double> triedValues(const FeedbackSearch& s) {
  std::vector<double> out;
  for (const auto& t : s.trials()) out.push_back(t.value);
  return out;
}

double chosen(const FeedbackSearch& s) { return s.best() >= 0 ? s.trials()[s.best()].value : std::nan(""); }

}  // namespace

TEST(FeedbackSearch, ExhaustiveTriesEveryCandidateInOneBatch) {
  FeedbackSearch s(range(0, 4, 1), {});
  auto batches = drive(s, [](double v) { return -(v - 3) * (v - 3); });
  ASSERT_EQ(batches.size(), 1u);
  EXPECT_EQ(batches[0], (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(chosen(s), 3);
  EXPECT_EQ(s.stop(), FeedbackSearch::Stop::AllTried);
  EXPECT_STREQ(FeedbackSearch::stopName(s.stop()), "all_tried");
}

TEST(FeedbackSearch, InitialCandidatesComeFirstAndAreNotRepeated) {
  FeedbackSearch s(range(0, 4, 1), {2.0, 7.5, NAN, 2.0});
  auto batches = drive(s, [](double v) { return v == 7.5 ? 100.0 : v; });
  ASSERT_EQ(batches.size(), 2u);
  EXPECT_EQ(batches[0], (std::vector<double>{2.0, 7.5}));  // NaN skipped, duplicate dropped
  EXPECT_EQ(batches[1], (std::vector<double>{0, 1, 3, 4}));  // 2 was tried already
  EXPECT_EQ(chosen(s), 7.5);                                   // an initial value may lie outside the range
}

TEST(FeedbackSearch, GoodEnoughStopsAtTheFirstCandidateInOrderThatReachesIt) {
  FeedbackSpec f = range(0, 10, 1);
  f.good_enough = 5.0;
  FeedbackSearch s(f, {3.0});
  auto batches = drive(s, [](double v) { return v; });  // score = value
  EXPECT_EQ(triedValues(s), (std::vector<double>{3, 0, 1, 2, 4, 5}));
  EXPECT_EQ(chosen(s), 5);
  EXPECT_EQ(s.stop(), FeedbackSearch::Stop::GoodEnough);
  // At least S when maximizing, at most S when minimizing; the initial value alone can end it.
  f.maximize = false;
  f.good_enough = 3.0;
  FeedbackSearch m(f, {3.0});
  drive(m, [](double v) { return v; });
  EXPECT_EQ(triedValues(m), (std::vector<double>{3}));
  EXPECT_EQ(m.stop(), FeedbackSearch::Stop::GoodEnough);
}

TEST(FeedbackSearch, ReportingFalseLeavesTheRestOfTheBatchUntried) {
  FeedbackSpec f = range(0, 10, 1);
  f.good_enough = 0.5;
  FeedbackSearch s(f, {});
  auto batch = s.nextBatch();
  ASSERT_EQ(batch.size(), 11u);
  EXPECT_TRUE(s.report(0.1));
  EXPECT_FALSE(s.report(0.9));
  EXPECT_TRUE(s.finished());
  EXPECT_TRUE(s.nextBatch().empty());
  EXPECT_EQ(s.trials().size(), 2u);
}

TEST(FeedbackSearch, NaNAndInfiniteScoresAreInvalid) {
  FeedbackSearch s(range(0, 3, 1), {});
  drive(s, [](double v) { return v == 3 ? INFINITY : v == 2 ? NAN : v; });
  EXPECT_EQ(chosen(s), 1);
  EXPECT_TRUE(std::isnan(s.trials()[3].score));
  FeedbackSearch none(range(0, 3, 1), {});
  drive(none, [](double) { return NAN; });
  EXPECT_EQ(none.best(), -1);
}

TEST(FeedbackSearch, TiesGoToTheCandidateTriedFirst) {
  FeedbackSearch s(range(0, 4, 1), {4.0});
  drive(s, [](double v) { return v == 1 || v == 4 ? 1.0 : 0.0; });
  EXPECT_EQ(chosen(s), 4);  // tried first, as the initial value
}

TEST(FeedbackSearch, ExplicitCoarseToFine) {
  // As the calibration's detection: the grid 30, 60, ... 210, then +-10 in steps of 5 around the best.
  FeedbackSpec f = range(30, 210, 5, "coarse_to_fine");
  f.coarse_step = 30;
  f.fine_radius = 10;
  FeedbackSearch s(f, {});
  auto batches = drive(s, [](double v) { return -std::abs(v - 102); });
  ASSERT_EQ(batches.size(), 2u);
  EXPECT_EQ(batches[0], (std::vector<double>{30, 60, 90, 120, 150, 180, 210}));
  EXPECT_EQ(batches[1], (std::vector<double>{80, 85, 95, 100}));
  EXPECT_EQ(chosen(s), 100);
  EXPECT_EQ(s.stop(), FeedbackSearch::Stop::Finished);
  EXPECT_STREQ(FeedbackSearch::stopName(s.stop()), "finished");
  EXPECT_EQ(s.candidates(), 37u);
}

TEST(FeedbackSearch, FineStepsCentreOnTheBestEvenOffTheGridAndStayInTheRange) {
  FeedbackSpec f = range(30, 210, 5, "coarse_to_fine");
  f.coarse_step = 30;
  f.fine_radius = 10;
  FeedbackSearch off(f, {117});
  auto batches = drive(off, [](double v) { return v == 117 ? 1.0 : 0.0; });
  ASSERT_EQ(batches.size(), 3u);
  EXPECT_EQ(batches[2], (std::vector<double>{107, 112, 122, 127}));
  FeedbackSearch edge(f, {});
  batches = drive(edge, [](double v) { return -v; });
  EXPECT_EQ(batches[1], (std::vector<double>{35, 40}));  // not 20, 25: outside from..to
}

TEST(FeedbackSearch, ExplicitCoarseToFineWithoutAnyScoreSkipsTheFinePass) {
  FeedbackSpec f = range(0, 100, 1, "coarse_to_fine");
  f.coarse_step = 25;
  f.fine_radius = 5;
  FeedbackSearch s(f, {});
  auto batches = drive(s, [](double) { return NAN; });
  EXPECT_EQ(batches.size(), 1u);
  EXPECT_EQ(s.best(), -1);
  EXPECT_EQ(s.stop(), FeedbackSearch::Stop::Finished);
}

TEST(FeedbackSearch, HalvingCoarseToFineFindsAUnimodalOptimum) {
  FeedbackSearch s(range(0, 200, 1, "coarse_to_fine"), {});
  auto batches = drive(s, [](double v) { return -(v - 137) * (v - 137); });
  EXPECT_EQ(chosen(s), 137);
  EXPECT_LT(s.trials().size(), 40u);
  EXPECT_EQ(batches[0].size(), 15u);  // 0, 15, ..., 195 and 200
  for (size_t i = 1; i < batches.size(); ++i) EXPECT_LE(batches[i].size(), 2u);
}

TEST(FeedbackSearch, HalvingFallsBackToEveryCandidateWhenTheGridMissesTheBand) {
  FeedbackSearch s(range(0, 100, 1, "coarse_to_fine"), {});
  drive(s, [](double v) { return v == 56 ? 1.0 : NAN; });  // between grid points 55 and 66
  EXPECT_EQ(chosen(s), 56);
  EXPECT_EQ(s.trials().size(), 101u);
  EXPECT_EQ(s.stop(), FeedbackSearch::Stop::AllTried);
}

TEST(FeedbackSearch, NormaliseRoundsLikeTheProperty) {
  FeedbackSearch s(range(0, 3, 1), {1.4}, [](double v) { return std::round(v); });
  auto batches = drive(s, [](double v) { return v; });
  EXPECT_EQ(batches[0], (std::vector<double>{1}));
  EXPECT_EQ(batches[1], (std::vector<double>{0, 2, 3}));
}

TEST(FeedbackSearch, CancelStopsAndMisuseIsALogicError) {
  FeedbackSearch s(range(0, 3, 1), {});
  auto batch = s.nextBatch();
  EXPECT_THROW(s.nextBatch(), std::logic_error);  // the batch was not reported
  s.report(1.0);
  s.cancel();
  EXPECT_EQ(s.stop(), FeedbackSearch::Stop::Cancelled);
  EXPECT_TRUE(s.nextBatch().empty());
  EXPECT_THROW(s.report(1.0), std::logic_error);
}
