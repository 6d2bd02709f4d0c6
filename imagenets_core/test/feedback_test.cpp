// Feedback (paper 3.4): a generic engine feature on any numeric property.
#include <gtest/gtest.h>
#include <imagenets/FeedbackTrace.h>
#include <std_msgs/Float64.h>

#include "imagenets/executor.h"
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
  // Empty or inverted range, step <= 0, unknown score block.
  has(loadError(sweepNet("{property: value, from: 5, to: 1, score: score.score}")), "range from 5 to 1 is inverted");
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
