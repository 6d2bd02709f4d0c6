// invokeBlock, the one way every host runs a block: required inputs checked, errors caught and
// named, outputs taken only as declared, the result recorded in one BlockStats.
#include <gtest/gtest.h>
#include <std_msgs/Float64.h>
#include <chrono>
#include <cmath>
#include <thread>

#include "imagenets/block_invocation.h"
#include "imagenets/registry.h"
#include "imagenets/time.h"
#include "test_blocks.h"

using namespace imagenets;

namespace {

Value number(double v) {
  auto msg = boost::make_shared<std_msgs::Float64>();
  msg->data = v;
  return PortType::of<std_msgs::Float64>().wrap(boost::shared_ptr<const std_msgs::Float64>(msg));
}

}  // namespace

TEST(BlockInvocation, RunsTheBlockAndTimesIt) {
  auto block = BlockRegistry::instance().create("test/Scale");
  block->setProperty("gain", 3.0);
  BlockInvocation run = invokeBlock(*block, "s", {number(2)}, block->propertySnapshot());
  ASSERT_EQ(run.status, BlockStatus::Ok) << run.message;
  EXPECT_TRUE(run.processed);
  EXPECT_GE(run.ms, 0.0);
  ASSERT_EQ(run.outputs.size(), 1u);
  EXPECT_DOUBLE_EQ(run.outputs[0].as<std_msgs::Float64>()->data, 6.0);
  BlockStats stats;
  stats.record(run.status, run.message, run.ms, run.processed);
  EXPECT_EQ(stats.runs, 1u);
  EXPECT_EQ(stats.failures, 0u);
}

TEST(BlockInvocation, AMissingRequiredInputIsNamedAndTheBlockNotCalled) {
  imagenets::test::resetCalls();
  auto block = BlockRegistry::instance().create("test/Add");
  // `b` is optional: only `a` is required.
  BlockInvocation run = invokeBlock(*block, "add", {Value(), number(1)}, block->propertySnapshot());
  EXPECT_EQ(run.status, BlockStatus::NotRun);
  EXPECT_EQ(run.missing_input, 0);
  EXPECT_EQ(run.error, "input 'a' has no value");
  EXPECT_FALSE(run.processed);
  EXPECT_EQ(imagenets::test::calls("add"), 0);
  EXPECT_EQ(invokeBlock(*block, "add", {number(1)}, block->propertySnapshot()).status, BlockStatus::Ok);
}

TEST(BlockInvocation, AnErrorIsCaughtNamedAndCounted) {
  auto block = BlockRegistry::instance().create("test/Scale");
  block->setProperty("fail", true);
  BlockInvocation run = invokeBlock(*block, "s", {number(2)}, block->propertySnapshot());
  EXPECT_EQ(run.status, BlockStatus::Failed);
  EXPECT_EQ(run.error, "asked to fail");
  EXPECT_EQ(run.message, "block 's' (test/Scale): asked to fail");
  EXPECT_FALSE(run.outputs[0]);
  BlockStats stats;
  stats.record(run.status, run.message, run.ms, run.processed);
  EXPECT_EQ(stats.runs, 1u);
  EXPECT_EQ(stats.failures, 1u);
  EXPECT_EQ(stats.last_error, run.message);
}

TEST(BlockInvocation, CancelledOnlyWhenTheRunWas) {
  // A block that stops on cancel when the run was not cancelled has failed.
  class StopsEarly : public Block {
   public:
    void process(Context&) override { throw RunCancelled(); }
  } block;
  BlockInvocation run = invokeBlock(block, "stop", {}, {});
  EXPECT_EQ(run.status, BlockStatus::Failed);
  EXPECT_FALSE(run.cancelled);
  run = invokeBlock(block, "stop", {}, {}, {RunChannel{{}, [] { return true; }}});
  EXPECT_EQ(run.status, BlockStatus::NotRun);
  EXPECT_TRUE(run.cancelled);
  EXPECT_EQ(run.message, "cancelled");
}

// Wall time and CPU time are measured apart: a block that waits costs time but no CPU, a block
// that computes costs CPU; the stats keep both.
TEST(BlockInvocation, MeasuresTheCallingThreadsCpuTimeBesideTheWallTime) {
  class Waits : public Block {
   public:
    void process(Context&) override { std::this_thread::sleep_for(std::chrono::milliseconds(30)); }
  } waits;
  BlockInvocation run = invokeBlock(waits, "waits", {}, waits.propertySnapshot());
  ASSERT_EQ(run.status, BlockStatus::Ok) << run.message;
  EXPECT_GE(run.ms, 30.0);
  EXPECT_LT(run.cpu_ms, 15.0);

  class Computes : public Block {
   public:
    // Until the thread itself has used 20 ms of CPU, however long that takes on a busy machine.
    void process(Context&) override {
      const double start = threadCpuMs();
      volatile double x = 0;
      while (threadCpuMs() - start < 20.0) {
        for (int i = 0; i < 1000; ++i) x = x + 1e-9 * i;
      }
    }
  } computes;
  run = invokeBlock(computes, "computes", {}, computes.propertySnapshot());
  ASSERT_EQ(run.status, BlockStatus::Ok) << run.message;
  EXPECT_GE(run.cpu_ms, 20.0);
  EXPECT_GE(run.ms, run.cpu_ms);
  BlockStats stats;
  stats.record(run.status, run.message, run.ms, run.processed, run.cpu_ms);
  EXPECT_EQ(stats.last_cpu_ms, run.cpu_ms);
  EXPECT_EQ(stats.last_ms, run.ms);
  // The means go over every run.
  const BlockInvocation waited = invokeBlock(waits, "waits", {}, waits.propertySnapshot());
  stats.record(waited.status, waited.message, waited.ms, waited.processed, waited.cpu_ms);
  EXPECT_DOUBLE_EQ(stats.mean_cpu_ms, (run.cpu_ms + waited.cpu_ms) / 2);
  EXPECT_DOUBLE_EQ(stats.mean_ms, (run.ms + waited.ms) / 2);
  EXPECT_EQ(stats.last_cpu_ms, waited.cpu_ms);
  // Not asked for: no clock read, the CPU figures of the stats stay as they were.
  InvocationOptions no_cpu;
  no_cpu.cpu_time = false;
  const BlockInvocation unmeasured = invokeBlock(computes, "computes", {}, computes.propertySnapshot(), no_cpu);
  ASSERT_EQ(unmeasured.status, BlockStatus::Ok) << unmeasured.message;
  EXPECT_TRUE(std::isnan(unmeasured.cpu_ms));
  stats.record(unmeasured.status, unmeasured.message, unmeasured.ms, unmeasured.processed, unmeasured.cpu_ms);
  EXPECT_EQ(stats.runs, 3u);
  EXPECT_EQ(stats.cpu_runs, 2u);
  EXPECT_EQ(stats.last_cpu_ms, waited.cpu_ms);
  EXPECT_DOUBLE_EQ(stats.mean_cpu_ms, (run.cpu_ms + waited.cpu_ms) / 2);
}
