// Run events (block started / finished / cached, feedback trial, repetition, run finished) and
// cancel. Cancels come from inside an observer at a known event, so every test is deterministic.
#include <algorithm>
#include <fstream>
#include <mutex>

#include <gtest/gtest.h>
#include <imagenets/FeedbackTrace.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>

#include "imagenets/executor.h"
#include "test_blocks.h"

using namespace imagenets;
using imagenets::test::calls;

namespace {

std::unique_ptr<Executor> load(const std::string& yaml, int threads = 2) {
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "events.yaml", "")), ExecutorOptions{threads});
}

std::string dir() { return ::testing::TempDir(); }
void write(const std::string& name, const std::string& yaml) { std::ofstream(dir() + "/" + name) << yaml; }
std::unique_ptr<Executor> loadFile(const std::string& name) {
  return std::make_unique<Executor>(Net::loadFile(dir() + "/" + name), ExecutorOptions{2});
}

// Collects events from any thread; `on` runs for each one (e.g. to cancel at a chosen event).
class Recorder {
 public:
  explicit Recorder(Executor& e, std::function<void(const RunEvent&)> on = {}) : e_(e), on_(std::move(on)) {
    id_ = e_.addObserver([this](const RunEvent& ev) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        events_.push_back(ev);
      }
      if (on_) on_(ev);
    });
  }
  ~Recorder() { e_.removeObserver(id_); }
  std::vector<RunEvent> events() {
    std::lock_guard<std::mutex> lock(mutex_);
    return events_;
  }
  std::vector<RunEvent> of(RunEventKind kind, const std::string& block = "") {
    std::vector<RunEvent> out;
    for (const auto& ev : events()) {
      if (ev.kind == kind && (block.empty() || ev.block == block)) out.push_back(ev);
    }
    return out;
  }
  // Position of the first event of `kind` for `block`, or -1.
  int position(RunEventKind kind, const std::string& block) {
    auto all = events();
    for (size_t i = 0; i < all.size(); ++i) {
      if (all[i].kind == kind && all[i].block == block) return static_cast<int>(i);
    }
    return -1;
  }
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    events_.clear();
  }

 private:
  Executor& e_;
  std::function<void(const RunEvent&)> on_;
  int id_;
  std::mutex mutex_;
  std::vector<RunEvent> events_;
};

const char* kChain = R"(
blocks:
  a: {type: test/Constant, properties: {value: 2}}
  b: {type: test/Scale, properties: {gain: 3}}
  c: {type: test/Scale, properties: {offset: 1}}
  d: {type: test/Constant, properties: {value: 7}}
links: [a.value -> b.in, b.out -> c.in]
)";

// x is tuned over 0..10 (sequentially, so trials come in order); `after` is downstream.
const char* kSweep = R"(
blocks:
  x:
    type: test/Constant
    feedback: {property: value, from: 0, to: 10, step: 1, score: score.score, parallel: false}
  score: {type: test/Parabola, properties: {peak: 4}}
  after: {type: test/Scale, properties: {gain: 10}}
links: [x.value -> score.x, x.value -> after.in]
)";

const char* kCount = R"(
blocks:
  counter: {type: test/Counter}
  out: {type: imagenets/SubNetOutput, properties: {port: n, type: std_msgs/Float64}}
links: [counter.count -> out.value]
)";

class RunEventsTest : public ::testing::Test {
 protected:
  void SetUp() override { imagenets::test::resetCalls(); }
};

}  // namespace

TEST_F(RunEventsTest, EveryBlockStartsThenFinishesInEventFlowAndTheRunFinishesLast) {
  auto e = load(kChain);
  Recorder rec(*e);
  ASSERT_TRUE(e->run().ok());
  for (const char* b : {"a", "b", "c", "d"}) {
    ASSERT_EQ(rec.of(RunEventKind::BlockStarted, b).size(), 1u) << b;
    auto finished = rec.of(RunEventKind::BlockFinished, b);
    ASSERT_EQ(finished.size(), 1u) << b;
    EXPECT_EQ(finished[0].stats.status, BlockStatus::Ok) << b;
    EXPECT_EQ(finished[0].stats.runs, 1u) << b;
    EXPECT_LT(rec.position(RunEventKind::BlockStarted, b), rec.position(RunEventKind::BlockFinished, b)) << b;
  }
  // b starts only once a has finished, c once b has.
  EXPECT_LT(rec.position(RunEventKind::BlockFinished, "a"), rec.position(RunEventKind::BlockStarted, "b"));
  EXPECT_LT(rec.position(RunEventKind::BlockFinished, "b"), rec.position(RunEventKind::BlockStarted, "c"));
  auto all = rec.events();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.back().kind, RunEventKind::RunFinished);
  EXPECT_EQ(all.back().message, "");
  EXPECT_EQ(rec.of(RunEventKind::RunFinished).size(), 1u);
  EXPECT_TRUE(rec.of(RunEventKind::BlockCached).empty());
}

TEST_F(RunEventsTest, BlocksARunDidNotNeedAreReportedCached) {
  auto e = load(kChain);
  e->run();
  Recorder rec(*e);
  e->setProperty("b", "gain", 5.0);
  ASSERT_TRUE(e->run().ok());
  std::vector<std::string> cached, finished;
  for (const auto& ev : rec.of(RunEventKind::BlockCached)) cached.push_back(ev.block);
  for (const auto& ev : rec.of(RunEventKind::BlockFinished)) finished.push_back(ev.block);
  std::sort(cached.begin(), cached.end());
  EXPECT_EQ(cached, (std::vector<std::string>{"a", "d"}));
  EXPECT_EQ(finished, (std::vector<std::string>{"b", "c"}));
  // The cached block's stats come along: it ran once, in the first run.
  EXPECT_EQ(rec.of(RunEventKind::BlockCached, "a")[0].stats.runs, 1u);
  EXPECT_EQ(rec.of(RunEventKind::BlockCached, "a")[0].stats.status, BlockStatus::Ok);
}

TEST_F(RunEventsTest, FinishedCarriesTheFailureAndTheBlocksItKeptFromRunning) {
  auto e = load(kChain);
  e->setProperty("b", "fail", true);
  Recorder rec(*e);
  e->run();
  auto b = rec.of(RunEventKind::BlockFinished, "b");
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0].stats.status, BlockStatus::Failed);
  EXPECT_EQ(b[0].stats.message, "block 'b' (test/Scale): asked to fail");
  auto c = rec.of(RunEventKind::BlockFinished, "c");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].stats.status, BlockStatus::NotRun);
  EXPECT_NE(c[0].stats.message.find("input 'in' has no value"), std::string::npos) << c[0].stats.message;
}

TEST_F(RunEventsTest, RemovedObserverHearsNothing) {
  auto e = load(kChain);
  size_t heard = 0;
  const int id = e->addObserver([&](const RunEvent&) { ++heard; });
  e->run();
  EXPECT_GT(heard, 0u);
  const size_t before = heard;
  e->removeObserver(id);
  e->runAll();
  EXPECT_EQ(heard, before);
}

TEST_F(RunEventsTest, EveryFeedbackTrialIsReportedWithValueScoreAndIndex) {
  auto e = load(kSweep);
  Recorder rec(*e);
  ASSERT_TRUE(e->run().ok());
  auto trials = rec.of(RunEventKind::FeedbackTrial);
  ASSERT_EQ(trials.size(), 11u);
  for (size_t i = 0; i < trials.size(); ++i) {
    EXPECT_EQ(trials[i].block, "x");
    EXPECT_EQ(trials[i].message, "value");
    EXPECT_EQ(trials[i].index, static_cast<int>(i) + 1);
    EXPECT_EQ(trials[i].count, 11);
    EXPECT_DOUBLE_EQ(trials[i].value, static_cast<double>(i));  // sequential: in candidate order
    EXPECT_DOUBLE_EQ(trials[i].score, -(trials[i].value - 4) * (trials[i].value - 4));
  }
  // The trials' inner runs are not block events; the region finishes once, after the sweep.
  EXPECT_EQ(rec.of(RunEventKind::BlockFinished, "score").size(), 1u);
  EXPECT_EQ(rec.of(RunEventKind::BlockStarted, "score").size(), 1u);
  EXPECT_LT(rec.position(RunEventKind::FeedbackTrial, "x"), rec.position(RunEventKind::BlockFinished, "x"));
  EXPECT_LT(rec.position(RunEventKind::BlockFinished, "x"), rec.position(RunEventKind::BlockStarted, "after"));
}

TEST_F(RunEventsTest, RepetitionsAndInnerBlocksOfASubNetReachTheOuterObserverWithTheirPath) {
  write("ev_count.yaml", kCount);
  write("ev_repeat.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: ev_count.yaml, repeat: 3}}\n");
  auto e = loadFile("ev_repeat.yaml");
  Recorder rec(*e);
  ASSERT_TRUE(e->run().ok());
  auto reps = rec.of(RunEventKind::Repetition);
  ASSERT_EQ(reps.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(reps[i].block, "loop");
    EXPECT_EQ(reps[i].index, i + 1);
    EXPECT_EQ(reps[i].count, 3);
    EXPECT_EQ(reps[i].message, "");
  }
  EXPECT_EQ(rec.of(RunEventKind::BlockFinished, "loop/counter").size(), 3u);
  EXPECT_EQ(rec.of(RunEventKind::BlockStarted, "loop/out").size(), 3u);
  EXPECT_EQ(rec.of(RunEventKind::BlockFinished, "loop").size(), 1u);
  // The inner runs' ends are not the outer run's end.
  EXPECT_EQ(rec.of(RunEventKind::RunFinished).size(), 1u);
  EXPECT_EQ(rec.events().back().kind, RunEventKind::RunFinished);
}

TEST_F(RunEventsTest, NestedSubNetsGiveTheWholePath) {
  write("ev_count.yaml", kCount);
  write("ev_middle.yaml", R"(
blocks:
  inner: {type: imagenets/SubNet, properties: {net: ev_count.yaml, repeat: 2}}
  out: {type: imagenets/SubNetOutput, properties: {port: n, type: std_msgs/Float64}}
links: [inner.n -> out.value]
)");
  write("ev_outer.yaml", "blocks:\n  outer: {type: imagenets/SubNet, properties: {net: ev_middle.yaml}}\n");
  auto e = loadFile("ev_outer.yaml");
  Recorder rec(*e);
  ASSERT_TRUE(e->run().ok());
  EXPECT_EQ(rec.of(RunEventKind::BlockFinished, "outer/inner/counter").size(), 2u);
  EXPECT_EQ(rec.of(RunEventKind::Repetition, "outer/inner").size(), 2u);
  EXPECT_EQ(rec.of(RunEventKind::Repetition, "outer").size(), 1u);
}

TEST_F(RunEventsTest, CancelBetweenBlocksLeavesTheRestOutOfDateAndTheNextRunResumes) {
  auto e = load(kChain, 1);  // one thread: d does not run beside a
  bool armed = true;
  Recorder rec(*e, [&](const RunEvent& ev) {
    if (armed && ev.kind == RunEventKind::BlockFinished && ev.block == "a") {
      armed = false;
      e->cancel();
    }
  });
  RunReport r = e->run();
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.failed.empty());
  EXPECT_EQ(calls("a"), 1);
  EXPECT_EQ(calls("b"), 0);
  EXPECT_EQ(calls("c"), 0);
  EXPECT_EQ(e->stats("b").status, BlockStatus::NotRun);
  EXPECT_EQ(e->stats("b").message, "cancelled");
  EXPECT_NE(std::find(r.not_run.begin(), r.not_run.end(), "c: cancelled"), r.not_run.end());
  EXPECT_EQ(rec.events().back().kind, RunEventKind::RunFinished);
  EXPECT_EQ(rec.events().back().message, "cancelled");

  // Usable afterwards: the next run does what was left, nothing more.
  RunReport next = e->run();
  EXPECT_FALSE(next.cancelled);
  EXPECT_TRUE(next.ok());
  EXPECT_EQ(calls("a"), 1);
  EXPECT_EQ(calls("b"), 1);
  EXPECT_EQ(calls("c"), 1);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("c.out")->data, 7.0);
}

TEST_F(RunEventsTest, CancelMidSweepStopsTheTrialsAndTheNextRunSweepsAgain) {
  auto e = load(kSweep);
  bool armed = true;  // cancels the first run only
  Recorder rec(*e, [&](const RunEvent& ev) {
    if (armed && ev.kind == RunEventKind::FeedbackTrial && ev.index == 3) {
      armed = false;
      e->cancel();
    }
  });
  RunReport r = e->run();
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.failed.empty());
  EXPECT_EQ(rec.of(RunEventKind::FeedbackTrial).size(), 3u);
  EXPECT_EQ(calls("x"), 3);  // no trial after the cancel
  EXPECT_EQ(calls("after"), 0);
  for (const char* b : {"x", "score", "after"}) {
    EXPECT_EQ(e->stats(b).status, BlockStatus::NotRun) << b;
    EXPECT_EQ(e->stats(b).message, "cancelled") << b;
  }
  EXPECT_FALSE(e->output("x.feedback_trace"));

  rec.clear();
  imagenets::test::resetCalls();
  RunReport next = e->run();
  ASSERT_TRUE(next.ok()) << next.failed[0];
  EXPECT_FALSE(next.cancelled);
  EXPECT_EQ(calls("x"), 11);
  EXPECT_EQ(e->output<FeedbackTrace>("x.feedback_trace")->trials, 11u);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 40.0);
}

TEST_F(RunEventsTest, CancelMidRepeatStopsBeforeTheNextRepetition) {
  write("ev_count.yaml", kCount);
  write("ev_repeat5.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: ev_count.yaml, repeat: 5}}\n");
  auto e = loadFile("ev_repeat5.yaml");
  bool armed = true;
  Recorder rec(*e, [&](const RunEvent& ev) {
    if (armed && ev.kind == RunEventKind::Repetition && ev.index == 2) {
      armed = false;
      e->cancel();
    }
  });
  RunReport r = e->run();
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.failed.empty());
  EXPECT_EQ(rec.of(RunEventKind::Repetition).size(), 2u);
  EXPECT_EQ(calls("counter"), 2);
  EXPECT_EQ(e->stats("loop").status, BlockStatus::NotRun);
  EXPECT_EQ(e->stats("loop").message, "cancelled");
  EXPECT_FALSE(e->output("loop.n_all"));

  RunReport next = e->run();
  ASSERT_TRUE(next.ok()) << next.failed[0];
  EXPECT_EQ(rec.of(RunEventKind::Repetition).size(), 7u);
  // The inner counter keeps counting: repetitions 3..7 of its life.
  EXPECT_EQ(e->output<std_msgs::Float64MultiArray>("loop.n_all")->data, (std::vector<double>{3, 4, 5, 6, 7}));
}

TEST_F(RunEventsTest, CancelInsideASubNetRepetitionReachesTheInnerRun) {
  write("ev_count.yaml", kCount);
  write("ev_repeat4.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: ev_count.yaml, repeat: 4}}\n");
  auto e = loadFile("ev_repeat4.yaml");
  int counter_done = 0;
  Recorder rec(*e, [&](const RunEvent& ev) {
    if (ev.kind == RunEventKind::BlockFinished && ev.block == "loop/counter" && ++counter_done == 2) e->cancel();
  });
  RunReport r = e->run();
  EXPECT_TRUE(r.cancelled);
  // The inner `out` of repetition 2 did not start: the cancel reached the inner executor.
  EXPECT_EQ(rec.of(RunEventKind::BlockStarted, "loop/out").size(), 1u);
  EXPECT_EQ(rec.of(RunEventKind::Repetition).size(), 1u);
  EXPECT_EQ(e->stats("loop").message, "cancelled");
  EXPECT_TRUE(e->run().ok());  // the observer cancels at the 2nd counter only, long past
}

TEST_F(RunEventsTest, CancelWhileIdleDoesNothing) {
  auto e = load(kChain);
  e->cancel();
  RunReport r = e->run();
  EXPECT_FALSE(r.cancelled);
  EXPECT_EQ(r.ran.size(), 4u);
}
