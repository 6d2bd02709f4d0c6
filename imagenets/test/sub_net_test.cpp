// Hierarchy (paper 3.5): nets as blocks, nested, in parallel, repeated.
#include <fstream>
#include <mutex>
#include <utility>

#include <geometry_msgs/PoseArray.h>
#include <gtest/gtest.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>

#include "imagenets/collectors.h"
#include "imagenets/executor.h"
#include "imagenets/graph.h"
#include "imagenets/net_wide_property.h"
#include "imagenets/registry.h"
#include "test_blocks.h"

using namespace imagenets;

namespace {

std::string dir() { return ::testing::TempDir(); }

void write(const std::string& name, const std::string& yaml) { std::ofstream(dir() + "/" + name) << yaml; }

std::unique_ptr<Executor> loadFile(const std::string& name, int threads = 2) {
  return std::make_unique<Executor>(Net::loadFile(dir() + "/" + name), ExecutorOptions{threads});
}

// in -> scale(gain) -> out: the innermost net.
const char* kDouble = R"(
blocks:
  in: {type: imagenets/SubNetInput, properties: {port: x, type: std_msgs/Float64}}
  scale: {type: test/Scale, properties: {gain: 2}}
  out: {type: imagenets/SubNetOutput, properties: {port: y, type: std_msgs/Float64}}
links: [in.value -> scale.in, scale.out -> out.value]
)";

// x -> the innermost net (level3.yaml) -> y.
const char* kLevel2 = R"(
blocks:
  in: {type: imagenets/SubNetInput, properties: {port: x, type: std_msgs/Float64}}
  inner: {type: imagenets/SubNet, properties: {net: level3.yaml}}
  out: {type: imagenets/SubNetOutput, properties: {port: y, type: std_msgs/Float64}}
links: [in.value -> inner.x, inner.y -> out.value]
)";

}  // namespace

TEST(SubNet, PortsComeFromSubNetInputAndOutputBlocks) {
  write("double.yaml", kDouble);
  write("outer.yaml", R"(
blocks:
  c: {type: test/Constant, properties: {value: 3}}
  sub: {type: imagenets/SubNet, properties: {net: double.yaml}}
  after: {type: test/Scale, properties: {offset: 1}}
links: [c.value -> sub.x, sub.y -> after.in]
)");
  auto e = loadFile("outer.yaml");
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 6.0);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 7.0);
}

TEST(SubNet, NetsWrittenWithTheFormerTypeNamesStillLoad) {
  write("double_former.yaml", R"(
blocks:
  in: {type: imagenets/ExecutorInput, properties: {port: x, type: std_msgs/Float64}}
  scale: {type: test/Scale, properties: {gain: 2}}
  out: {type: imagenets/ExecutorOutput, properties: {port: y, type: std_msgs/Float64}}
links: [in.value -> scale.in, scale.out -> out.value]
)");
  write("outer_former.yaml", R"(
blocks:
  c: {type: test/Constant, properties: {value: 4}}
  sub: {type: imagenets/Executor, properties: {net: double_former.yaml}}
links: [c.value -> sub.x]
)");
  auto e = loadFile("outer_former.yaml");
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 8.0);
  const BlockRegistry& registry = BlockRegistry::instance();
  ASSERT_NE(registry.find("imagenets/Executor"), nullptr);
  EXPECT_EQ(registry.find("imagenets/Executor")->type, "imagenets/SubNet");
  EXPECT_EQ(registry.find("imagenets/ExecutorInput")->type, "imagenets/SubNetInput");
  EXPECT_EQ(registry.find("imagenets/ExecutorOutput")->type, "imagenets/SubNetOutput");
  EXPECT_EQ(registry.find("imagenets/NoSuchBlock"), nullptr);
}

TEST(SubNet, AnOptionalInputMayStayWithoutAValue) {
  write("add.yaml", R"(
blocks:
  a: {type: imagenets/SubNetInput, properties: {port: a, type: std_msgs/Float64}}
  b: {type: imagenets/SubNetInput, properties: {port: b, type: std_msgs/Float64, optional: true}}
  add: {type: test/Add}
  sum: {type: imagenets/SubNetOutput, properties: {port: sum, type: std_msgs/Float64}}
links: [a.value -> add.a, b.value -> add.b, add.sum -> sum.value]
)");
  write("outer_optional.yaml", R"(
blocks:
  sub: {type: imagenets/SubNet, properties: {net: add.yaml}}
)");
  auto e = loadFile("outer_optional.yaml");
  const auto number = [](double v) {
    auto m = boost::make_shared<std_msgs::Float64>();
    m->data = v;
    return PortType::of<std_msgs::Float64>().wrap<std_msgs::Float64>(m);
  };
  // Without `a` (required) the block does not run; without `b` (optional) it does.
  e->setInput("sub.b", number(5));
  const RunReport without_a = e->run();
  ASSERT_EQ(without_a.not_run.size(), 1u);
  EXPECT_NE(without_a.not_run.front().find("input 'a' has no value"), std::string::npos) << without_a.not_run.front();
  e->setInput("sub.a", number(2));
  e->setInput("sub.b", Value());
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.sum")->data, 2.0);
  e->setInput("sub.b", number(5));
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.sum")->data, 7.0);
}

TEST(SubNet, OuterLinksAreTypeChecked) {
  write("double.yaml", kDouble);
  write("bad_outer.yaml", R"(
blocks:
  c: {type: test/Constant, feedback: {property: value, from: 0, to: 1, score: p.score}}
  p: {type: test/Parabola}
  sub: {type: imagenets/SubNet, properties: {net: double.yaml}}
links: [c.value -> p.x, c.feedback_trace -> sub.x]
)");
  try {
    Net::loadFile(dir() + "/bad_outer.yaml");
    FAIL();
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find("type mismatch: output is imagenets/FeedbackTrace, input is std_msgs/Float64"),
              std::string::npos)
        << e.what();
  }
}

TEST(SubNet, NestsThreeLevelsDeep) {
  write("level3.yaml", kDouble);
  write("level2.yaml", kLevel2);
  write("level1.yaml", R"(
blocks:
  in: {type: imagenets/SubNetInput, properties: {port: x, type: std_msgs/Float64}}
  inner: {type: imagenets/SubNet, properties: {net: level2.yaml}}
  twice: {type: imagenets/SubNet, properties: {net: level3.yaml}}
  out: {type: imagenets/SubNetOutput, properties: {port: y, type: std_msgs/Float64}}
links: [in.value -> inner.x, inner.y -> twice.x, twice.y -> out.value]
)");
  write("top.yaml", R"(
blocks:
  c: {type: test/Constant, properties: {value: 1.5}}
  sub: {type: imagenets/SubNet, properties: {net: level1.yaml}}
links: [c.value -> sub.x]
)");
  auto e = loadFile("top.yaml");
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 6.0);  // 1.5 * 2 * 2
  // Changing the outer input re-runs the nested nets.
  e->setProperty("c", "value", 2.0);
  e->run();
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 8.0);
}

TEST(SubNet, SelfInclusionIsRejectedWithTheChain) {
  write("self.yaml", "blocks:\n  me: {type: imagenets/SubNet, properties: {net: self.yaml}}\n");
  write("ping.yaml", "blocks:\n  pong: {type: imagenets/SubNet, properties: {net: pong.yaml}}\n");
  write("pong.yaml", "blocks:\n  ping: {type: imagenets/SubNet, properties: {net: ping.yaml}}\n");
  for (const char* name : {"self.yaml", "ping.yaml"}) {
    try {
      Net::loadFile(dir() + "/" + name);
      FAIL() << name << " loaded";
    } catch (const NetError& e) {
      const std::string text = e.what();
      EXPECT_NE(text.find("includes itself"), std::string::npos) << text;
      EXPECT_NE(text.find(std::string(name) + " -> "), std::string::npos) << text;
    }
  }
}

TEST(SubNet, TwoInstancesRunIndependentlyAndInParallel) {
  // Each instance holds a barrier that only opens when both instances are inside it at once.
  write("meet.yaml", R"(
blocks:
  in: {type: imagenets/SubNetInput, properties: {port: x, type: std_msgs/Float64}}
  meet: {type: test/Barrier, properties: {group: two_subnets, parties: 2}}
  scale: {type: test/Scale, properties: {gain: 3}}
  out: {type: imagenets/SubNetOutput, properties: {port: y, type: std_msgs/Float64}}
links: [in.value -> meet.in, in.value -> scale.in, scale.out -> out.value]
)");
  write("stereo.yaml", R"(
blocks:
  left_in: {type: test/Constant, properties: {value: 1}}
  right_in: {type: test/Constant, properties: {value: 2}}
  left: {type: imagenets/SubNet, properties: {net: meet.yaml}}
  right: {type: imagenets/SubNet, properties: {net: meet.yaml}}
links: [left_in.value -> left.x, right_in.value -> right.x]
)");
  auto e = loadFile("stereo.yaml", 2);
  RunReport r = e->run();
  ASSERT_TRUE(r.ok()) << r.failed[0];
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("left.y")->data, 3.0);
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("right.y")->data, 6.0);
}

TEST(SubNet, RepeatCollectsNResults) {
  write("count.yaml", R"(
blocks:
  counter: {type: test/Counter}
  out: {type: imagenets/SubNetOutput, properties: {port: n, type: std_msgs/Float64}}
links: [counter.count -> out.value]
)");
  write("repeat.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: count.yaml, repeat: 5}}\n");
  auto e = loadFile("repeat.yaml");
  ASSERT_TRUE(e->run().ok());
  auto all = e->output<std_msgs::Float64MultiArray>("loop.n_all");
  ASSERT_TRUE(all);
  EXPECT_EQ(all->data, (std::vector<double>{1, 2, 3, 4, 5}));
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("loop.n")->data, 5.0);
}

// A net whose counter fails every `fail_every`-th run, and hands out its count as `n`.
std::string counterNet(int fail_every) {
  return "blocks:\n  counter: {type: test/Counter, properties: {fail_every: " + std::to_string(fail_every) +
         "}}\n  out: {type: imagenets/SubNetOutput, properties: {port: n, type: std_msgs/Float64}}\n"
         "links: [counter.count -> out.value]\n";
}

TEST(SubNet, FailedRepetitionsAreLeftOutOrFailTheBlock) {
  // Every 2nd run of the inner counter fails: runs 2 and 4 of 5.
  write("flaky.yaml", counterNet(2));
  write("tolerant.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: flaky.yaml, repeat: 5, max_failures: 2}}\n");
  auto tolerant = loadFile("tolerant.yaml");
  ASSERT_TRUE(tolerant->run().ok());
  // Only the successful repetitions: a failed one does not repeat the previous result.
  EXPECT_EQ(tolerant->output<std_msgs::Float64MultiArray>("loop.n_all")->data, (std::vector<double>{1, 3, 5}));

  write("strict.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: flaky.yaml, repeat: 5, max_failures: 1}}\n");
  auto strict = loadFile("strict.yaml");
  const RunReport r = strict->run();
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_NE(r.failed[0].find("2 of 5 repetitions failed (max_failures 1); repetition 2:"), std::string::npos) << r.failed[0];
  EXPECT_NE(r.failed[0].find("run 2 failed on purpose"), std::string::npos) << r.failed[0];
  EXPECT_FALSE(strict->output<std_msgs::Float64MultiArray>("loop.n_all"));
}

// What a run's repetition events said (describe()), and "until" where the until net's `sum`
// finished, in the order they came.
class RepetitionLog {
 public:
  explicit RepetitionLog(Executor& e) {
    e.addObserver([this](const RunEvent& ev) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (ev.kind == RunEventKind::Repetition) {
        events_.push_back(describe(ev));
        statuses_.push_back(ev.stats.status);
      }
      if (ev.kind == RunEventKind::BlockFinished && ev.block == "loop/until/sum") events_.push_back("until");
    });
  }
  std::vector<std::string> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    statuses_.clear();
    return std::exchange(events_, {});
  }
  // Each repetition's status so far (the typed one: the event's text also holds the until net's answer).
  std::vector<BlockStatus> statuses() {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_;
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> events_;
  std::vector<BlockStatus> statuses_;
};

// An until net is asked only once a repetition has succeeded; until then the events say so.
TEST(SubNet, AnUntilNetIsNotAskedBeforeARepetitionSucceeded) {
  write("failing.yaml", counterNet(1));
  write("any_sum.yaml", R"(
blocks:
  n_all: {type: imagenets/SubNetInput, properties: {port: n_all, type: std_msgs/Float64MultiArray}}
  zero: {type: test/Constant, properties: {value: 0}}
  sum: {type: test/SumAtLeast}
  done: {type: imagenets/SubNetOutput, properties: {port: done, type: std_msgs/Bool}}
links: [n_all.value -> sum.values, zero.value -> sum.threshold, sum.reached -> done.value]
)");
  write("never_asked.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: failing.yaml, "
                            "max_failures: 3, until_net: any_sum.yaml, max_repeat: 3}}\n");
  auto e = loadFile("never_asked.yaml");
  RepetitionLog log(*e);
  ASSERT_TRUE(e->run().ok());  // every repetition failed, as max_failures allows
  EXPECT_EQ(log.statuses(), std::vector<BlockStatus>(3, BlockStatus::Failed));
  const std::vector<std::string> events = log.take();
  ASSERT_EQ(events.size(), 3u);
  EXPECT_NE(events[0].find("repetition 1 of 3 done (failed: "), std::string::npos) << events[0];
  EXPECT_NE(events[0].find("; until net not asked: no repetition has succeeded yet)"), std::string::npos) << events[0];
  EXPECT_EQ(events[2].find("until net"), std::string::npos) << events[2];  // none may follow the last
}

// Indices as numbers, so a test sees every repetition's (a library adds collectors for its types).
CollectorRegistration<std_msgs::Int32, std_msgs::Float64MultiArray> indices(
    [](const std::vector<std_msgs::Int32::ConstPtr>& items) {
      auto all = boost::make_shared<std_msgs::Float64MultiArray>();
      for (const auto& i : items) all->data.push_back(i->data);
      return all;
    });

// A net that hands out the index its input `k` is told.
const char* kIndex = R"(
blocks:
  k: {type: imagenets/SubNetInput, properties: {port: k, type: std_msgs/Int32}}
  out: {type: imagenets/SubNetOutput, properties: {port: index, type: std_msgs/Int32}}
links: [k.value -> out.value]
)";

TEST(SubNet, EachRepetitionIsToldItsIndexAndTheCountCanComeFromAnInput) {
  write("index.yaml", kIndex);
  write("indexed.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: index.yaml, repeat: 4, "
                        "repetition_input: k}}\n");
  auto e = loadFile("indexed.yaml");
  // The index port is fed by the block itself: it is not an input of the outer block.
  EXPECT_EQ(e->net().node(0).block->findInput("k"), nullptr);
  ASSERT_TRUE(e->run().ok());
  EXPECT_EQ(e->output<std_msgs::Float64MultiArray>("loop.index_all")->data, (std::vector<double>{0, 1, 2, 3}));

  write("counted.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: index.yaml, "
                        "repetition_input: k, repeat_from_input: true}}\n");
  auto counted = loadFile("counted.yaml");
  auto three = boost::make_shared<std_msgs::Int32>();
  three->data = 3;
  counted->setInput("loop.repeat", boost::shared_ptr<const std_msgs::Int32>(three));
  ASSERT_TRUE(counted->run().ok());
  EXPECT_EQ(counted->output<std_msgs::Float64MultiArray>("loop.index_all")->data, (std::vector<double>{0, 1, 2}));
  three->data = 0;
  counted->setInput("loop.repeat", boost::shared_ptr<const std_msgs::Int32>(three));
  const RunReport zero = counted->run();
  ASSERT_EQ(zero.failed.size(), 1u);
  EXPECT_NE(zero.failed[0].find("input 'repeat': 0 repetitions"), std::string::npos) << zero.failed[0];

  write("misnamed.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: index.yaml, "
                         "repetition_input: kk}}\n");
  try {
    Net::loadFile(dir() + "/misnamed.yaml");
    FAIL();
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find("property 'repetition_input'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no input port 'kk'"), std::string::npos) << e.what();
  }
}

// The index net with an input `target` it does not use itself (an until net's).
const char* kIndexTarget = R"(
blocks:
  k: {type: imagenets/SubNetInput, properties: {port: k, type: std_msgs/Int32}}
  target: {type: imagenets/SubNetInput, properties: {port: target, type: std_msgs/Float64}}
  out: {type: imagenets/SubNetOutput, properties: {port: index, type: std_msgs/Int32}}
links: [k.value -> out.value]
)";

// An until net: done when the indices so far (`index_all`) add up to the input `target`.
const char* kSumReached = R"(
blocks:
  index_all: {type: imagenets/SubNetInput, properties: {port: index_all, type: std_msgs/Float64MultiArray}}
  target: {type: imagenets/SubNetInput, properties: {port: target, type: std_msgs/Float64}}
  sum: {type: test/SumAtLeast}
  done: {type: imagenets/SubNetOutput, properties: {port: done, type: std_msgs/Bool}}
links: [index_all.value -> sum.values, target.value -> sum.threshold, sum.reached -> done.value]
)";

// Repeat until: past N repetitions one more at a time, until the until net says done.
TEST(SubNet, RepeatUntilTheUntilNetIsDoneOrMaxRepeatRan) {
  // The repeated net hands out its index; `target` is an input it does not use itself.
  write("index_target.yaml", kIndexTarget);
  // Its until net is fed from the block's input `target` and the collection `index_all` so far.
  write("sum_reached.yaml", kSumReached);
  write("until.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: index_target.yaml, repeat: 2, "
                      "repetition_input: k, until_net: sum_reached.yaml, max_repeat: 8}}\n");
  auto e = loadFile("until.yaml");
  RepetitionLog log(*e);
  auto target = [&](double t) {
    auto v = boost::make_shared<std_msgs::Float64>();
    v->data = t;
    e->setInput("loop.target", boost::shared_ptr<const std_msgs::Float64>(v));
  };
  // 0+1+2+3+4 = 10: asked after 2, 3, 4 and 5 repetitions; the until net's events are nested.
  target(10);
  ASSERT_TRUE(e->run().ok());
  EXPECT_EQ(e->output<std_msgs::Float64MultiArray>("loop.index_all")->data, (std::vector<double>{0, 1, 2, 3, 4}));
  // Each repetition's event says what the until net said after it; its status stays ok.
  EXPECT_EQ(log.statuses(), std::vector<BlockStatus>(5, BlockStatus::Ok));
  EXPECT_EQ(log.take(), (std::vector<std::string>{"loop: repetition 1 of 8 done", "until",
                                                 "loop: repetition 2 of 8 done (until net: not done)", "until",
                                                 "loop: repetition 3 of 8 done (until net: not done)", "until",
                                                 "loop: repetition 4 of 8 done (until net: not done)", "until",
                                                 "loop: repetition 5 of 8 done (until net: done)"}));
  // Done at once: the N repetitions always run.
  target(0);
  ASSERT_TRUE(e->run().ok());
  EXPECT_EQ(e->output<std_msgs::Float64MultiArray>("loop.index_all")->data, (std::vector<double>{0, 1}));
  // Never done: max_repeat ends it (the until net is not asked after the last one).
  target(1000);
  ASSERT_TRUE(e->run().ok());
  EXPECT_EQ(e->output<std_msgs::Float64MultiArray>("loop.index_all")->data.size(), 8u);
  // An until net that fails is not done either; every repetition's event says why, not only the
  // until net's own block event.
  target(-1);
  log.take();
  ASSERT_TRUE(e->run().ok());
  EXPECT_EQ(e->output<std_msgs::Float64MultiArray>("loop.index_all")->data.size(), 8u);
  const std::vector<std::string> events = log.take();
  ASSERT_EQ(events.size(), 8u + 6u);  // 8 repetitions, the until net asked after the 2nd..7th
  EXPECT_EQ(events[2], "loop: repetition 2 of 8 done (until net failed: block 'sum' (test/SumAtLeast): input "
                       "'threshold': -1.000000 is below 0)");
  EXPECT_EQ(events.back(), "loop: repetition 8 of 8 done");
  e->setProperty("loop", "max_repeat", 1);
  const RunReport below = e->run();
  ASSERT_EQ(below.failed.size(), 1u);
  EXPECT_NE(below.failed[0].find("property 'max_repeat': 1 is below the 2 repetitions"), std::string::npos)
      << below.failed[0];

  // From inputs, as the calibration plan gives them.
  write("until_counted.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: index_target.yaml, "
                              "repetition_input: k, repeat_from_input: true, until_net: sum_reached.yaml}}\n");
  auto counted = loadFile("until_counted.yaml");
  auto number = [](int n) {
    auto v = boost::make_shared<std_msgs::Int32>();
    v->data = n;
    return boost::shared_ptr<const std_msgs::Int32>(v);
  };
  auto six = boost::make_shared<std_msgs::Float64>();
  six->data = 6;
  counted->setInput("loop.target", boost::shared_ptr<const std_msgs::Float64>(six));
  counted->setInput("loop.repeat", number(1));
  counted->setInput("loop.max_repeat", number(3));
  ASSERT_TRUE(counted->run().ok());  // 0+1+2 = 3 < 6: stopped by max_repeat
  EXPECT_EQ(counted->output<std_msgs::Float64MultiArray>("loop.index_all")->data, (std::vector<double>{0, 1, 2}));
  counted->setInput("loop.max_repeat", number(10));
  ASSERT_TRUE(counted->run().ok());  // 0+1+2+3 = 6
  EXPECT_EQ(counted->output<std_msgs::Float64MultiArray>("loop.index_all")->data, (std::vector<double>{0, 1, 2, 3}));
}

TEST(SubNet, AnUntilNetWhosePortsDoNotFitIsNamed) {
  write("index.yaml", kIndex);
  write("sum_reached.yaml", kSumReached);  // wants `target`, which this block does not have
  write("until_no_done.yaml", R"(
blocks:
  index_all: {type: imagenets/SubNetInput, properties: {port: index_all, type: std_msgs/Float64MultiArray}}
  stop: {type: imagenets/SubNetOutput, properties: {port: stop, type: std_msgs/Float64MultiArray}}
links: [index_all.value -> stop.value]
)");
  auto error = [](const std::string& until) {
    write("until_bad.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: index.yaml, "
                            "repetition_input: k, until_net: " + until + ", max_repeat: 3}}\n");
    try {
      Net::loadFile(dir() + "/until_bad.yaml");
    } catch (const NetError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string unmatched = error("sum_reached.yaml");
  EXPECT_NE(unmatched.find("property 'until_net': input 'target' of"), std::string::npos) << unmatched;
  EXPECT_NE(unmatched.find("sum_reached.yaml"), std::string::npos) << unmatched;
  EXPECT_NE(unmatched.find("(have: index_all)"), std::string::npos) << unmatched;
  const std::string no_done = error("until_no_done.yaml");
  EXPECT_NE(no_done.find("property 'until_net'"), std::string::npos) << no_done;
  EXPECT_NE(no_done.find("has no output 'done'"), std::string::npos) << no_done;
}

TEST(SubNet, WithEnoughAllowedFailuresAFailedRunIsAResultNotAnError) {
  write("always_fails.yaml", R"(
blocks:
  counter: {type: test/Counter, properties: {fail_every: 1}}
  out: {type: imagenets/SubNetOutput, properties: {port: n, type: std_msgs/Float64}}
links: [counter.count -> out.value]
)");
  write("tolerated.yaml", "blocks:\n  once: {type: imagenets/SubNet, properties: {net: always_fails.yaml, "
                          "max_failures: 1}}\n");
  auto e = loadFile("tolerated.yaml");
  ASSERT_TRUE(e->run().ok());
  EXPECT_FALSE(e->output<std_msgs::Float64>("once.n"));
  auto why = e->output<std_msgs::String>("once.failure");
  ASSERT_TRUE(why);
  EXPECT_NE(why->data.find("run 1 failed on purpose"), std::string::npos) << why->data;
}

TEST(SubNet, RepeatBelowOneIsAClearError) {
  write("count.yaml", "blocks:\n  counter: {type: test/Counter}\n");
  write("repeat0.yaml", "blocks:\n  loop: {type: imagenets/SubNet, properties: {net: count.yaml, repeat: 0}}\n");
  try {
    Net::loadFile(dir() + "/repeat0.yaml");
    FAIL();
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find("property 'repeat': value 0 is out of range [1, 100000]"), std::string::npos)
        << e.what();
  }
}

TEST(SubNet, InlineYamlNet) {
  auto spec = parseNetText(R"(
blocks:
  c: {type: test/Constant, properties: {value: 4}}
  sub:
    type: imagenets/SubNet
    properties:
      net_yaml: |
        blocks:
          in: {type: imagenets/SubNetInput, properties: {port: x, type: std_msgs/Float64}}
          scale: {type: test/Scale, properties: {gain: 0.5}}
          out: {type: imagenets/SubNetOutput, properties: {port: y, type: std_msgs/Float64}}
        links: [in.value -> scale.in, scale.out -> out.value]
links: [c.value -> sub.x]
)", "inline.yaml", "");
  Executor e(Net::build(spec), ExecutorOptions{2});
  ASSERT_TRUE(e.run().ok());
  EXPECT_DOUBLE_EQ(e.output<std_msgs::Float64>("sub.y")->data, 2.0);
}

// One value for every block that declares a property of that name, sub-nets at any depth included
// (e.g. the robot description of a calibration node's nets).
TEST(SubNet, APropertyIsSetOnEveryBlockOfTheNetTreeThatHasIt) {
  write("level3.yaml", kDouble);
  write("level2.yaml", kLevel2);
  write("tree.yaml", R"(
blocks:
  c: {type: test/Constant, properties: {value: 3}}
  sub: {type: imagenets/SubNet, properties: {net: level2.yaml}}
  after: {type: test/Scale, properties: {offset: 1}}
links: [c.value -> sub.x, sub.y -> after.in]
)");
  auto e = loadFile("tree.yaml");
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 7.0);  // 3 * 2 * 1 + 1
  EXPECT_EQ(setPropertyInNetTree(*e, "gain", "5"), (std::vector<std::string>{"sub/inner/scale", "after"}));
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("after.out")->data, 76.0);  // 3 * 5 * 5 + 1
  // A filter on the property's declaration: here only integer properties named `gain` (none).
  EXPECT_TRUE(setPropertyInNetTree(*e, "gain", "7", [](const PropertySpec& p) { return p.kind() == PropertyKind::Int; })
                  .empty());
  // A sub-net's until net is part of the tree: its threshold here is the target times `gain`.
  write("index_target.yaml", kIndexTarget);
  write("scaled_sum_reached.yaml", R"(
blocks:
  index_all: {type: imagenets/SubNetInput, properties: {port: index_all, type: std_msgs/Float64MultiArray}}
  target: {type: imagenets/SubNetInput, properties: {port: target, type: std_msgs/Float64}}
  scale: {type: test/Scale}
  sum: {type: test/SumAtLeast}
  done: {type: imagenets/SubNetOutput, properties: {port: done, type: std_msgs/Bool}}
links: [index_all.value -> sum.values, target.value -> scale.in, scale.out -> sum.threshold, sum.reached -> done.value]
)");
  write("until_tree.yaml", R"(
blocks:
  c: {type: test/Constant, properties: {value: 10}}
  loop: {type: imagenets/SubNet, properties: {net: index_target.yaml, repeat: 2, repetition_input: k,
                                                until_net: scaled_sum_reached.yaml, max_repeat: 8}}
links: [c.value -> loop.target]
)");
  auto u = loadFile("until_tree.yaml");
  ASSERT_TRUE(u->run().ok());
  EXPECT_EQ(u->output<std_msgs::Float64MultiArray>("loop.index_all")->data.size(), 5u);  // 0+1+2+3+4 >= 10
  EXPECT_EQ(setPropertyInNetTree(*u, "gain", "0.5"), (std::vector<std::string>{"loop/until/scale"}));
  ASSERT_TRUE(u->run().ok());
  EXPECT_EQ(u->output<std_msgs::Float64MultiArray>("loop.index_all")->data.size(), 4u);  // 0+1+2+3 >= 5
  // A value that is not valid for a block names the block and the property.
  try {
    setPropertyInNetTree(*e, "gain", "not a number");
    FAIL();
  } catch (const std::exception& err) {
    EXPECT_NE(std::string(err.what()).find("gain"), std::string::npos) << err.what();
    EXPECT_NE(std::string(err.what()).find("scale"), std::string::npos) << err.what();
  }
}

// One value replaced by another wherever blocks of one type hold it, sub-nets included (e.g. a
// robot's controller action in place of the default name the nets were written with).
TEST(SubNet, AValueIsReplacedWhereBlocksOfTheTypeHoldIt) {
  write("level3.yaml", kDouble);  // its scale: gain 2
  write("level2.yaml", kLevel2);
  write("replace_tree.yaml", R"(
blocks:
  c: {type: test/Constant, properties: {value: 3}}
  sub: {type: imagenets/SubNet, properties: {net: level2.yaml}}
  after: {type: test/Scale, properties: {gain: 2, offset: 1}}
  other: {type: test/Scale, properties: {gain: 3}}
links: [c.value -> sub.x, sub.y -> after.in, after.out -> other.in]
)");
  auto e = loadFile("replace_tree.yaml");
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("other.out")->data, 39.0);  // (3 * 2 * 2 + 1) * 3
  // Compared as values: "2.0" is the 2 written in the files; the block holding 3 keeps it.
  EXPECT_EQ(replacePropertyValueInNetTree(*e, "test/Scale", "gain", "2.0", "5"),
            (std::vector<std::string>{"sub/inner/scale", "after"}));
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("other.out")->data, 228.0);  // (3 * 5 * 5 + 1) * 3
  EXPECT_TRUE(replacePropertyValueInNetTree(*e, "test/Scale", "gain", "2", "7").empty());  // none holds 2 now
  // Another type's blocks are left alone, whatever they hold.
  EXPECT_TRUE(replacePropertyValueInNetTree(*e, "test/Constant", "gain", "5", "7").empty());
  EXPECT_TRUE(replacePropertyValueInNetTree(*e, "test/Constant", "value", "4", "7").empty());
  EXPECT_EQ(replacePropertyValueInNetTree(*e, "test/Constant", "value", "3", "1"), (std::vector<std::string>{"c"}));
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("other.out")->data, 78.0);  // (1 * 5 * 5 + 1) * 3
  // A value not valid there names the block and the property; nothing is changed.
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"5", "not a number"}, {"five", "2"}}) {
    try {
      replacePropertyValueInNetTree(*e, "test/Scale", "gain", from, to);
      ADD_FAILURE() << from << " -> " << to;
    } catch (const NetError& err) {
      EXPECT_NE(std::string(err.what()).find("gain"), std::string::npos) << err.what();
      EXPECT_NE(std::string(err.what()).find("block 'scale'"), std::string::npos) << err.what();
    }
  }
  ASSERT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("other.out")->data, 78.0);
}

TEST(SubNet, GraphDrawsSubNetsAsClustersAndFeedbackDashed) {
  write("double.yaml", kDouble);
  write("drawn.yaml", R"(
blocks:
  c: {type: test/Constant, feedback: {property: value, from: 0, to: 2, score: sub.y}}
  sub: {type: imagenets/SubNet, properties: {net: double.yaml}}
links: [c.value -> sub.x]
)");
  const std::string dot = toDot(*Net::loadFile(dir() + "/drawn.yaml"), true);
  EXPECT_NE(dot.find("subgraph cluster_"), std::string::npos) << dot;
  EXPECT_NE(dot.find("style=dashed"), std::string::npos);
  EXPECT_NE(dot.find("feedback: value (max)"), std::string::npos);
  // The sub-net's path as written beside the net, not the machine's absolute path.
  EXPECT_NE(dot.find("net = double.yaml<"), std::string::npos) << dot;
  EXPECT_NE(dot.find("sub: double.yaml"), std::string::npos) << dot;
  EXPECT_EQ(dot.find("= /"), std::string::npos) << dot;
  EXPECT_EQ(dot.find(": /"), std::string::npos) << dot;
}
