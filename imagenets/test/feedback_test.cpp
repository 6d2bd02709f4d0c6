// Feedback (paper 3.4): a generic engine feature on any numeric property.
#include <gtest/gtest.h>
#include <imagenets/FeedbackTrace.h>
#include <std_msgs/Float64.h>

#include "imagenets/executor.h"
#include "imagenets/graph.h"
#include "test_blocks.h"

using namespace imagenets;

namespace {

std::unique_ptr<Executor> load(const std::string& yaml, int threads = 2) {
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "fb.yaml", "")), ExecutorOptions{threads});
}

std::string loadError(const std::string& yaml) {
  try {
    load(yaml);
  } catch (const NetError& e) {
    return e.what();
  }
  return "";
}

// x (tuned) -> score = -(x - peak)^2; `after` consumes x downstream of the score region.
std::string sweepNet(const std::string& feedback, double peak = 1.5, const std::string& parabola_extra = "") {
  return R"(
blocks:
  x:
    type: test/Constant
    feedback: )" + feedback + R"(
  score: {type: test/Parabola, properties: {peak: )" + std::to_string(peak) + parabola_extra + R"(}}
  after: {type: test/Scale, properties: {gain: 10}}
links:
  - x.value -> score.x
  - x.value -> after.in
)";
}

class FeedbackTest : public ::testing::Test {
 protected:
  void SetUp() override { imagenets::test::resetCalls(); }
};

}  // namespace

TEST_F(FeedbackTest, FindsTheKnownOptimumAndContinuesWithIt) {
  auto e = load(sweepNet("{property: value, from: -5, to: 5, step: 0.5, score: score.score, goal: maximize}"));
  RunReport r = e->run();
  ASSERT_TRUE(r.ok()) << r.failed[0];
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("x.value")->data, 1.5);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("score.score")->data, 0.0);
  // Downstream continues with the best candidate's outputs, without re-running the trials.
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 15.0);
  EXPECT_EQ(imagenets::test::calls("x"), 21);
  EXPECT_EQ(imagenets::test::calls("score"), 21);
  EXPECT_EQ(imagenets::test::calls("after"), 1);

  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  ASSERT_TRUE(trace);
  EXPECT_EQ(trace->values.size(), 21u);
  EXPECT_EQ(trace->scores.size(), 21u);
  EXPECT_EQ(trace->candidates, 21u);
  EXPECT_EQ(trace->trials, 21u);
  EXPECT_DOUBLE_EQ(trace->values.front(), -5.0);
  EXPECT_DOUBLE_EQ(trace->values.back(), 5.0);
  EXPECT_DOUBLE_EQ(trace->scores.front(), -42.25);
  EXPECT_TRUE(trace->found);
  EXPECT_DOUBLE_EQ(trace->chosen_value, 1.5);
  EXPECT_EQ(trace->property, "value");
  EXPECT_EQ(trace->score, "score.score");
}

TEST_F(FeedbackTest, RunningTheTunedBlockOnlyRunsItsSweepButNotWhatFollows) {
  auto e = load(sweepNet("{property: value, from: -5, to: 5, step: 0.5, score: score.score, goal: maximize}"));
  e->run();
  RunReport r = e->runBlockOnly("x");
  ASSERT_TRUE(r.ok()) << r.failed[0];
  EXPECT_EQ(imagenets::test::calls("x"), 42);  // a second sweep of 21 candidates
  EXPECT_EQ(imagenets::test::calls("after"), 1);
  // `after` is out of date: the next run runs it and nothing of the sweep.
  EXPECT_EQ(e->run().ran, (std::vector<std::string>{"after"}));
  EXPECT_EQ(imagenets::test::calls("x"), 42);
}

TEST_F(FeedbackTest, MinimizeFindsTheMinimum) {
  auto e = load(sweepNet("{property: value, values: [3, -1, 7, 2], score: score.score, goal: minimize}", 2.0));
  e->run();
  EXPECT_DOUBLE_EQ(e->output<FeedbackTrace>("x.feedback_trace")->chosen_value, 7.0);
}

TEST_F(FeedbackTest, ParallelAndSequentialSweepsAgreeExactly) {
  auto seq = load(sweepNet("{property: value, from: 0, to: 3, step: 0.1, score: score.score, parallel: false}", 1.7), 1);
  auto par = load(sweepNet("{property: value, from: 0, to: 3, step: 0.1, score: score.score, parallel: true}", 1.7), 2);
  seq->run();
  par->run();
  auto a = seq->output<FeedbackTrace>("x.feedback_trace");
  auto b = par->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(a->values, b->values);
  EXPECT_EQ(a->scores, b->scores);
  EXPECT_EQ(a->chosen_value, b->chosen_value);
  EXPECT_EQ(seq->output<std_msgs::Float64>("after.out")->data, par->output<std_msgs::Float64>("after.out")->data);
}

TEST_F(FeedbackTest, TiesResolveToTheFirstCandidate) {
  // 1.0 and 1.5 are equally far from 1.25.
  auto e = load(sweepNet("{property: value, values: [0, 1.0, 1.5, 3], score: score.score}", 1.25));
  e->run();
  EXPECT_DOUBLE_EQ(e->output<FeedbackTrace>("x.feedback_trace")->chosen_value, 1.0);
}

TEST_F(FeedbackTest, CoarseToFineAgreesOnAUnimodalScoreInFewerTrials) {
  auto full = load(sweepNet("{property: value, from: 0, to: 200, step: 1, score: score.score}", 137));
  auto fast = load(sweepNet("{property: value, from: 0, to: 200, step: 1, score: score.score, search: coarse_to_fine}", 137));
  full->run();
  fast->run();
  auto a = full->output<FeedbackTrace>("x.feedback_trace");
  auto b = fast->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(a->chosen_value, 137.0);
  EXPECT_EQ(b->chosen_value, 137.0);
  EXPECT_EQ(a->trials, 201u);
  EXPECT_LT(b->trials, 40u);
  EXPECT_EQ(b->candidates, 201u);
}

TEST_F(FeedbackTest, NoValidCandidateIsAVisibleStateNotACrash) {
  auto e = load(sweepNet("{property: value, from: 0, to: 5, score: score.score}", 1.0, ", valid_from: 100"));
  RunReport r = e->run();
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_NE(r.failed[0].find("feedback: no valid candidate"), std::string::npos) << r.failed[0];
  EXPECT_EQ(e->stats("x").status, BlockStatus::Failed);
  EXPECT_FALSE(e->output("x.value"));
  EXPECT_FALSE(e->output("after.out"));  // downstream sees no output
  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  ASSERT_TRUE(trace);  // the trace still shows what was tried
  EXPECT_FALSE(trace->found);
  EXPECT_EQ(trace->values.size(), 6u);
  EXPECT_TRUE(std::isnan(trace->scores[0]));
}

TEST_F(FeedbackTest, WhenTheTunedBlockFailsInEveryTrialItsStatsKeepWhy) {
  auto e = load(R"(
blocks:
  c: {type: test/Constant, properties: {value: 1}}
  x:
    type: test/Scale
    properties: {fail: true}
    feedback: {property: gain, from: 0, to: 5, score: score.score}
  score: {type: test/Parabola}
links: [c.value -> x.in, x.out -> score.x]
)");
  RunReport r = e->run();
  ASSERT_EQ(r.failed.size(), 1u);
  // The verdict is "no valid candidate"; the reason stays readable as the last process() failure.
  const BlockStats stats = e->stats("x");
  EXPECT_NE(stats.message.find("feedback: no valid candidate"), std::string::npos) << stats.message;
  EXPECT_EQ(stats.failures, 6u);
  EXPECT_EQ(stats.last_error, "block 'x' (test/Scale): asked to fail");
}

TEST_F(FeedbackTest, ChangingABlockInsideTheRegionRerunsTheSweep) {
  auto e = load(sweepNet("{property: value, from: 0, to: 4, score: score.score}", 1.0));
  e->run();
  EXPECT_DOUBLE_EQ(e->output<FeedbackTrace>("x.feedback_trace")->chosen_value, 1.0);
  e->setProperty("score", "peak", 3.0);
  e->run();
  EXPECT_DOUBLE_EQ(e->output<FeedbackTrace>("x.feedback_trace")->chosen_value, 3.0);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 30.0);
}

TEST_F(FeedbackTest, ValidationErrorsAreNamed) {
  auto has = [](const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "missing \"" << part << "\" in:\n" << text;
  };
  // Non-numeric property.
  has(loadError(R"(
blocks:
  c: {type: test/Constant}
  s: {type: test/Scale, feedback: {property: fail, values: [0, 1], score: p.score}}
  p: {type: test/Parabola}
links: [c.value -> s.in, s.out -> p.x]
)"),
      "block 's': feedback: property 'fail' is bool, not numeric");
  // Unknown property.
  has(loadError(sweepNet("{property: nope, from: 0, to: 1, score: score.score}")),
      "block 'x': feedback: unknown property 'nope'");
  // Score port not downstream.
  has(loadError(R"(
blocks:
  x: {type: test/Constant, feedback: {property: value, from: 0, to: 1, score: p.score}}
  c: {type: test/Constant}
  p: {type: test/Parabola}
links: [c.value -> p.x]
)"),
      "score port p.score is not downstream of block 'x'");
  // Score port of the wrong type.
  has(loadError(R"(
blocks:
  x: {type: test/Constant, feedback: {property: value, from: 0, to: 1, score: y.feedback_trace}}
  y: {type: test/Scale, feedback: {property: gain, from: 0, to: 1, score: p.score}}
  p: {type: test/Parabola}
links: [x.value -> y.in, y.out -> p.x]
)"),
      "score port y.feedback_trace is imagenets/FeedbackTrace, not std_msgs/Float64");
  // Step <= 0, empty values, unknown score block.
  has(loadError(sweepNet("{property: value, from: 0, to: 1, step: 0, score: score.score}")), "step 0 must be > 0");
  has(loadError(sweepNet("{property: value, from: 0, to: 1, step: -1, score: score.score}")), "step -1 must be > 0");
  has(loadError(sweepNet("{property: value, values: [], score: score.score}")), "'values' is empty");
  has(loadError(sweepNet("{property: value, from: 0, to: 1, score: nothing.score}")),
      "score block 'nothing' does not exist");
  // Candidates outside the property's range.
  has(loadError(R"(
blocks:
  c: {type: test/Constant}
  s: {type: test/Scale, feedback: {property: offset, from: 0, to: 2000, step: 100, score: p.score}}
  p: {type: test/Parabola}
links: [c.value -> s.in, s.out -> p.x]
)"),
      "candidate for 'offset': value 1100 is out of range [-1000, 1000]");
}

TEST_F(FeedbackTest, ManyParallelSweepsNeverDeadlock) {
  // Trials nest (sweep -> trial -> blocks) on one pool whose waiting threads help run queued
  // tasks; a lost wake-up there once hung real nets. Hammer it: a hang fails by ctest's timeout.
  auto e = load(sweepNet("{property: value, from: 0, to: 30, step: 1, score: score.score}", 7), 3);
  for (int i = 0; i < 150; ++i) {
    e->setProperty("score", "peak", static_cast<double>(i % 31));
    ASSERT_TRUE(e->run().ok());
    ASSERT_DOUBLE_EQ(e->output<FeedbackTrace>("x.feedback_trace")->chosen_value, i % 31);
  }
}

// --- initial, good_enough, explicit coarse-to-fine -------------------------------------------

namespace {
// `guess` (outside the region) provides the initial candidate; x is tuned; score = -(x - peak)^2.
std::string initialNet(const std::string& feedback, double guess, double peak) {
  return R"(
blocks:
  guess: {type: test/Constant, properties: {value: )" + std::to_string(guess) + R"(}}
  x:
    type: test/Constant
    feedback: )" + feedback + R"(
  score: {type: test/Parabola, properties: {peak: )" + std::to_string(peak) + R"(}}
  after: {type: test/Scale, properties: {gain: 10}}
links:
  - x.value -> score.x
  - x.value -> after.in
)";
}
}  // namespace

TEST_F(FeedbackTest, InitialFromAPortIsTriedFirstAndGoodEnoughStopsThere) {
  auto e = load(initialNet("{property: value, from: 0, to: 100, score: score.score, initial: guess.value, "
                           "good_enough: -1}", 42, 42.5));
  ASSERT_TRUE(e->run().ok());
  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values, (std::vector<double>{42}));  // -0.25 >= -1: no sweep at all
  EXPECT_EQ(trace->stop_reason, "good_enough");
  EXPECT_EQ(trace->chosen_value, 42);
  EXPECT_EQ(imagenets::test::calls("x"), 1);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 420);
  // The providing block changes: the sweep runs again from its new value.
  e->setProperty("guess", "value", 7.0);
  ASSERT_TRUE(e->run().ok());
  trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values.front(), 7);
  EXPECT_EQ(trace->chosen_value, 42);  // 7 is not good enough: the sweep reaches 42 (first >= -1 in order)
  EXPECT_EQ(trace->values.size(), 43u);  // 7, then 0..42 without 7
}

TEST_F(FeedbackTest, GoodEnoughWhenMinimizingMeansAtMost) {
  auto e = load(sweepNet("{property: value, from: 0, to: 10, score: score.score, goal: minimize, good_enough: -20}", 5));
  e->run();
  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values, (std::vector<double>{0}));  // -(0 - 5)^2 = -25 <= -20
  EXPECT_EQ(trace->stop_reason, "good_enough");
}

TEST_F(FeedbackTest, InitialConstantsAndOrderTried) {
  auto e = load(sweepNet("{property: value, from: 0, to: 4, score: score.score, initial: [3, 1]}", 2));
  e->run();
  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values, (std::vector<double>{3, 1, 0, 2, 4}));
  EXPECT_EQ(trace->stop_reason, "all_tried");
  EXPECT_EQ(trace->chosen_value, 2);
}

TEST_F(FeedbackTest, ExplicitCoarseToFineTriesTheGridThenAroundTheBest) {
  auto e = load(sweepNet("{property: value, from: 30, to: 210, step: 5, search: coarse_to_fine, coarse_step: 30, "
                         "fine_radius: 10, score: score.score}", 101));
  e->run();
  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values, (std::vector<double>{30, 60, 90, 120, 150, 180, 210, 80, 85, 95, 100}));
  EXPECT_EQ(trace->chosen_value, 100);
  EXPECT_EQ(trace->stop_reason, "finished");
  EXPECT_EQ(trace->candidates, 37u);
}

// `to` below `from`: the candidates run downwards, e.g. the thresholds most likely to succeed first;
// the fine pass stays within the range.
TEST_F(FeedbackTest, ADescendingRangeIsTriedFromItsFirstEnd) {
  auto e = load(sweepNet("{property: value, from: 210, to: 30, step: 5, search: coarse_to_fine, coarse_step: 30, "
                         "fine_radius: 10, score: score.score}", 201));
  ASSERT_TRUE(e->run().ok());
  auto trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values, (std::vector<double>{210, 180, 150, 120, 90, 60, 30, 200, 205}));  // not 215, 220
  EXPECT_EQ(trace->chosen_value, 200);
  EXPECT_EQ(trace->candidates, 37u);
  // Good enough stops at the first candidate in that order.
  e = load(sweepNet("{property: value, from: 4, to: 0, score: score.score, good_enough: -1}", 1.5));
  ASSERT_TRUE(e->run().ok());
  trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values, (std::vector<double>{4, 3, 2}));  // -(2 - 1.5)^2 >= -1; 1 would score the same
  EXPECT_EQ(trace->chosen_value, 2);
  // The halving search on a descending range.
  e = load(sweepNet("{property: value, from: 10, to: 0, search: coarse_to_fine, score: score.score}", 3));
  ASSERT_TRUE(e->run().ok());
  trace = e->output<FeedbackTrace>("x.feedback_trace");
  EXPECT_EQ(trace->values.front(), 10);
  EXPECT_EQ(trace->chosen_value, 3);
  EXPECT_LT(trace->values.size(), 11u);
}

TEST_F(FeedbackTest, ParallelAndSequentialAgreeExactlyWithInitialGoodEnoughAndCoarseToFine) {
  for (const std::string extra : {"search: coarse_to_fine, coarse_step: 0.5, fine_radius: 0.3",
                                  "good_enough: -0.05", "search: coarse_to_fine, good_enough: -0.01",
                                  "search: coarse_to_fine"}) {
    const std::string fb = "{property: value, from: 0, to: 3, step: 0.1, score: score.score, initial: guess.value, " +
                           extra + ", parallel: ";
    auto seq = load(initialNet(fb + "false}", 2.95, 1.73), 1);
    auto par = load(initialNet(fb + "true}", 2.95, 1.73), 3);
    ASSERT_TRUE(seq->run().ok());
    ASSERT_TRUE(par->run().ok());
    auto a = seq->output<FeedbackTrace>("x.feedback_trace");
    auto b = par->output<FeedbackTrace>("x.feedback_trace");
    EXPECT_EQ(a->values, b->values) << extra;
    EXPECT_EQ(a->scores, b->scores) << extra;
    EXPECT_EQ(a->stop_reason, b->stop_reason) << extra;
    EXPECT_EQ(a->chosen_value, b->chosen_value) << extra;
    EXPECT_EQ(a->values.front(), 2.95) << extra;  // the initial value first
    EXPECT_EQ(seq->output<std_msgs::Float64>("after.out")->data, par->output<std_msgs::Float64>("after.out")->data);
  }
}

TEST_F(FeedbackTest, AnInitialPortWithoutAValueAddsNoCandidate) {
  auto e = load(R"(
blocks:
  broken: {type: test/Scale, properties: {fail: true}}
  c: {type: test/Constant}
  x: {type: test/Constant, feedback: {property: value, values: [1, 2], score: score.score, initial: broken.out}}
  score: {type: test/Parabola, properties: {peak: 2}}
links: [c.value -> broken.in, x.value -> score.x]
)");
  RunReport r = e->run();
  ASSERT_EQ(r.failed.size(), 1u);  // `broken` only; the sweep went on
  EXPECT_EQ(e->output<FeedbackTrace>("x.feedback_trace")->values, (std::vector<double>{1, 2}));
}

TEST_F(FeedbackTest, NewKeysValidationErrorsNameFileLineBlockKeyAndValue) {
  auto has = [](const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "missing \"" << part << "\" in:\n" << text;
  };
  const std::string x = "fb.yaml:5: block 'x': feedback: ";
  has(loadError(sweepNet("{property: value, from: 0, to: 9, score: score.score, good_enough: high}")),
      x + "good_enough 'high' is not a number");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, score: score.score, initial: [1, 'a b']}")),
      x + "initial 'a b' is neither a number nor block.port");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, score: score.score, initial: {a: 1}}")),
      x + "initial '{a: 1}' is neither a number nor block.port");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, score: score.score, coarse_step: 3, fine_radius: 1}")),
      x + "coarse_step and fine_radius need search: coarse_to_fine (search is exhaustive)");
  has(loadError(sweepNet("{property: value, values: [1, 2], search: coarse_to_fine, score: score.score, "
                         "coarse_step: 3, fine_radius: 1}")),
      x + "coarse_step and fine_radius need from/to/step, not 'values'");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, search: coarse_to_fine, score: score.score, coarse_step: 3}")),
      x + "give both coarse_step and fine_radius (only coarse_step is given)");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, search: coarse_to_fine, score: score.score, "
                         "coarse_step: 0, fine_radius: -2}")),
      x + "coarse_step 0 must be > 0");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, search: coarse_to_fine, score: score.score, "
                         "coarse_step: 0, fine_radius: -2}")),
      x + "fine_radius -2 must be >= 0");
  has(loadError(sweepNet("{property: value, from: 0, to: 9, score: score.score, parallel: maybe}")),
      x + "parallel 'maybe' is neither true nor false");
  has(loadError(sweepNet("{property: value, from: zero, to: 9, score: score.score}")),
      x + "from 'zero' is not a number");
  // Initial ports: checked when the net is built.
  const std::string i = "fb.yaml:6: block 'x': feedback: initial ";
  has(loadError(initialNet("{property: value, from: 0, to: 9, score: score.score, initial: nothing.value}", 1, 1)),
      i + "nothing.value: no block named 'nothing'");
  has(loadError(initialNet("{property: value, from: 0, to: 9, score: score.score, initial: guess.nope}", 1, 1)),
      i + "guess.nope: block 'guess' has no output port 'nope' (outputs: value [std_msgs/Float64])");
  has(loadError(initialNet("{property: value, from: 0, to: 9, score: score.score, initial: x.feedback_trace}", 1, 1)),
      i + "x.feedback_trace is imagenets/FeedbackTrace, not std_msgs/Float64");
  has(loadError(initialNet("{property: value, from: 0, to: 9, score: score.score, initial: score.score}", 1, 1)),
      i + "score.score: block 'score' is not upstream of the feedback region of 'x'");
  has(loadError(initialNet("{property: value, from: 0, to: 9, score: score.score, initial: after.out}", 1, 1)),
      i + "after.out: block 'after' is not upstream of the feedback region of 'x'");
  has(loadError(R"(
blocks:
  c: {type: test/Constant}
  s: {type: test/Scale, feedback: {property: offset, from: 0, to: 10, score: p.score, initial: 5000}}
  p: {type: test/Parabola}
links: [c.value -> s.in, s.out -> p.x]
)"),
      "block 's': feedback: initial 5000 for 'offset': value 5000 is out of range [-1000, 1000]");
}

TEST_F(FeedbackTest, TheGraphDrawsWhereTheInitialCandidateComesFrom) {
  const std::string dot =
      toDot(*Net::build(parseNetText(initialNet("{property: value, from: 0, to: 9, score: score.score, "
                                                "initial: guess.value}", 1, 1), "fb.yaml", "")));
  // guess is b0, x is b1: a dotted edge from guess's output to the tuned block.
  EXPECT_NE(dot.find("b0:o_value:e -> b1 [style=dotted, color=\"#555555\", label=\"initial value\"]"), std::string::npos)
      << dot;
}
