// Event flow, incremental re-execution, single-block runs, error isolation, true parallelism and
// the embedding API.
#include <gtest/gtest.h>
#include <std_msgs/Float64.h>

#include "imagenets/executor.h"
#include "test_blocks.h"

using namespace imagenets;
using imagenets::test::calls;

namespace {

std::unique_ptr<Executor> load(const std::string& yaml, int threads = 2) {
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "test.yaml", "")), ExecutorOptions{threads});
}

double value(const Executor& e, const std::string& port) { return e.output<std_msgs::Float64>(port)->data; }

// a -> b -> c, and d on its own.
const char* kChain = R"(
blocks:
  a: {type: test/Constant, properties: {value: 2}}
  b: {type: test/Scale, properties: {gain: 3}}
  c: {type: test/Scale, properties: {offset: 1}}
  d: {type: test/Constant, properties: {value: 7}}
links:
  - a.value -> b.in
  - b.out -> c.in
)";

class ExecutorTest : public ::testing::Test {
 protected:
  void SetUp() override { imagenets::test::resetCalls(); }
};

}  // namespace

TEST_F(ExecutorTest, RunsEveryBlockOnceInEventFlow) {
  auto e = load(kChain);
  RunReport r = e->run();
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.ran.size(), 4u);
  EXPECT_DOUBLE_EQ(value(*e, "c.out"), 7.0);  // 2 * 3 + 1
  for (const char* b : {"a", "b", "c", "d"}) EXPECT_EQ(calls(b), 1) << b;
  // Nothing changed: a second run runs nothing.
  EXPECT_TRUE(e->run().ran.empty());
  EXPECT_EQ(calls("a"), 1);
}

TEST_F(ExecutorTest, PropertyChangeReRunsOnlyThatBlockAndDownstream) {
  auto e = load(kChain);
  e->run();
  e->setProperty("b", "gain", 10.0);
  RunReport r = e->run();
  EXPECT_EQ(r.ran, (std::vector<std::string>{"b", "c"}));
  EXPECT_EQ(calls("a"), 1);
  EXPECT_EQ(calls("b"), 2);
  EXPECT_EQ(calls("c"), 2);
  EXPECT_EQ(calls("d"), 1);
  EXPECT_DOUBLE_EQ(value(*e, "c.out"), 21.0);
}

TEST_F(ExecutorTest, PropertyChangeIsValidatedAndNamed) {
  auto e = load(kChain);
  try {
    e->setPropertyText("b", "gain", "lots");
    FAIL();
  } catch (const NetError& err) {
    EXPECT_NE(std::string(err.what()).find("block 'b': property 'gain': expected double, got 'lots'"),
              std::string::npos)
        << err.what();
  }
  EXPECT_THROW(e->setProperty("zz", "gain", 1.0), NetError);
}

TEST_F(ExecutorTest, MarkOutOfDateReRunsTheBlockAndDownstreamOnTheNextRun) {
  auto e = load(kChain);
  e->run();
  e->markOutOfDate("b");
  EXPECT_EQ(calls("b"), 1);  // nothing runs until the next run
  EXPECT_EQ(e->run().ran, (std::vector<std::string>{"b", "c"}));
  EXPECT_EQ(calls("a"), 1);
  try {
    e->markOutOfDate("zz");
    FAIL();
  } catch (const NetError& err) {
    EXPECT_NE(std::string(err.what()).find("no block named 'zz'"), std::string::npos) << err.what();
  }
}

TEST_F(ExecutorTest, RunBlockRunsItAndItsDownstream) {
  auto e = load(kChain);
  e->run();
  RunReport r = e->runBlock("b");
  EXPECT_EQ(r.ran, (std::vector<std::string>{"b", "c"}));
  EXPECT_EQ(calls("a"), 1);
  EXPECT_EQ(calls("b"), 2);
  EXPECT_EQ(e->stats("b").runs, 2u);
  EXPECT_EQ(e->stats("a").runs, 1u);
}

TEST_F(ExecutorTest, RunBlockOnlyRunsThatBlockAloneOnItsCurrentInputs) {
  auto e = load(kChain);
  e->run();
  e->setProperty("a", "value", 5.0);  // a is out of date now, but b runs on a's cached 2
  RunReport r = e->runBlockOnly("b");
  EXPECT_EQ(r.ran, (std::vector<std::string>{"b"}));
  EXPECT_EQ(calls("a"), 1);
  EXPECT_EQ(calls("b"), 2);
  EXPECT_EQ(calls("c"), 1);
  EXPECT_DOUBLE_EQ(value(*e, "b.out"), 6.0);
  EXPECT_DOUBLE_EQ(value(*e, "c.out"), 7.0);  // still from the first run
  // The next run refreshes what was out of date: a (its property) and everything below it.
  EXPECT_EQ(e->run().ran, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_DOUBLE_EQ(value(*e, "c.out"), 16.0);
  // After a single run of b, only its downstream c is out of date.
  e->runBlockOnly("b");
  EXPECT_EQ(e->run().ran, (std::vector<std::string>{"c"}));
  EXPECT_EQ(calls("b"), 4);
  EXPECT_THROW(e->runBlockOnly("zz"), NetError);
}

TEST_F(ExecutorTest, RunBlockOnlyWithoutInputValuesSaysWhichInputIsMissing) {
  auto e = load(kChain);
  RunReport r = e->runBlockOnly("c");
  EXPECT_TRUE(r.ran.empty());
  ASSERT_EQ(r.not_run.size(), 1u);
  EXPECT_NE(r.not_run[0].find("c: input 'in' has no value (block 'b' produced none)"), std::string::npos)
      << r.not_run[0];
  EXPECT_EQ(calls("c"), 0);
}

TEST_F(ExecutorTest, FailingBlockIsReportedAndItsDownstreamNotRun) {
  auto e = load(kChain);
  e->setProperty("b", "fail", true);
  RunReport r = e->run();
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_EQ(r.failed[0], "block 'b' (test/Scale): asked to fail");
  ASSERT_EQ(r.not_run.size(), 1u);
  EXPECT_NE(r.not_run[0].find("c: input 'in' has no value (block 'b' produced none)"), std::string::npos)
      << r.not_run[0];
  EXPECT_EQ(e->stats("b").status, BlockStatus::Failed);
  EXPECT_EQ(e->stats("c").status, BlockStatus::NotRun);
  EXPECT_EQ(calls("c"), 0);
  EXPECT_FALSE(e->output("c.out"));
  EXPECT_DOUBLE_EQ(value(*e, "d.value"), 7.0);  // the rest ran
  // The executor keeps working: fix the block, run again.
  e->setProperty("b", "fail", false);
  EXPECT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(value(*e, "c.out"), 7.0);
  EXPECT_EQ(e->stats("b").last_error, "block 'b' (test/Scale): asked to fail");
  EXPECT_EQ(e->stats("b").status, BlockStatus::Ok);
}

TEST_F(ExecutorTest, IndependentBlocksRunInParallel) {
  // Each barrier waits (up to 10 s) for the other to be inside process() too: this only passes
  // when two threads run them at the same time.
  auto e = load(R"(
blocks:
  left:  {type: test/Barrier, properties: {group: parallel_test, parties: 2}}
  right: {type: test/Barrier, properties: {group: parallel_test, parties: 2}}
)", 2);
  RunReport r = e->run();
  EXPECT_TRUE(r.ok()) << (r.failed.empty() ? "" : r.failed[0]);
  EXPECT_TRUE(e->output("left.value"));
  EXPECT_TRUE(e->output("right.value"));
}

TEST_F(ExecutorTest, StatisticsCountRunsAndTimes) {
  auto e = load(kChain);
  e->run();
  e->runBlock("a");
  BlockStats s = e->stats("a");
  EXPECT_EQ(s.runs, 2u);
  EXPECT_GE(s.mean_ms, 0.0);
  EXPECT_EQ(s.status, BlockStatus::Ok);
}

TEST_F(ExecutorTest, EmbeddingSetInputsRunReadOutputs) {
  // A net with an unlinked input, fed from C++.
  auto e = load(R"(
blocks:
  scale: {type: test/Scale, properties: {gain: 2}}
  add: {type: test/Add}
links:
  - scale.out -> add.a
)");
  RunReport first = e->run();  // no input yet: nothing can run, nothing crashes
  EXPECT_TRUE(first.ran.empty());
  EXPECT_EQ(e->stats("scale").status, BlockStatus::NotRun);

  auto in = boost::make_shared<std_msgs::Float64>();
  in->data = 5;
  e->setInput<std_msgs::Float64>("scale.in", in);
  e->setInput<std_msgs::Float64>("add.b", in);
  EXPECT_TRUE(e->run().ok());
  EXPECT_DOUBLE_EQ(value(*e, "add.sum"), 15.0);
  e->setProperty("scale", "gain", 3.0);
  e->run();
  EXPECT_DOUBLE_EQ(value(*e, "add.sum"), 20.0);
  // Linked inputs cannot be set from outside; types are checked.
  EXPECT_THROW(e->setInput<std_msgs::Float64>("add.a", in), NetError);
}

TEST_F(ExecutorTest, OutputValuesAreSharedNotCopied) {
  auto e = load(kChain);
  e->run();
  EXPECT_EQ(e->output("c.out").data.get(), e->output("c.out").data.get());
}
