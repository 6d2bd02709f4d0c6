#include "test_blocks.h"

#include <chrono>
#include <condition_variable>
#include <thread>

#include <numeric>

#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>

#include "imagenets/registry.h"

namespace imagenets {
namespace test {
namespace {

std::mutex calls_mutex;
std::map<std::string, int> call_counts;

void count(const Context& ctx) {
  std::lock_guard<std::mutex> lock(calls_mutex);
  ++call_counts[ctx.blockName()];
}

boost::shared_ptr<std_msgs::Float64> number(double v) {
  auto msg = boost::make_shared<std_msgs::Float64>();
  msg->data = v;
  return msg;
}

// Outputs `value`.
class Constant : public Block {
 public:
  Constant() {
    addOutput<std_msgs::Float64>("value", "the property");
    addProperty<double>("value", 1.0, "number to output").range(-1e9, 1e9);
  }
  void process(Context& ctx) override {
    count(ctx);
    ctx.output("value", number(ctx.property<double>("value")));
  }
};

// in * gain + offset; fails when `fail` is set.
class Scale : public Block {
 public:
  Scale() {
    addInput<std_msgs::Float64>("in", "a number");
    addOutput<std_msgs::Float64>("out", "in * gain + offset");
    addProperty<double>("gain", 1.0, "factor").range(-1000, 1000);
    addProperty<int>("offset", 0, "added").range(-1000, 1000);
    addProperty<bool>("fail", false, "throw instead of computing");
  }
  void process(Context& ctx) override {
    count(ctx);
    if (ctx.property<bool>("fail")) throw BlockError("asked to fail");
    ctx.output("out", number(ctx.input<std_msgs::Float64>("in")->data * ctx.property<double>("gain") +
                                 ctx.property<int>("offset")));
  }
};

// a + b (b optional).
class Add : public Block {
 public:
  Add() {
    addInput<std_msgs::Float64>("a", "first");
    addOptionalInput<std_msgs::Float64>("b", "second (0 when absent)");
    addOutput<std_msgs::Float64>("sum", "a + b");
  }
  void process(Context& ctx) override {
    count(ctx);
    double b = ctx.hasInput("b") ? ctx.input<std_msgs::Float64>("b")->data : 0.0;
    ctx.output("sum", number(ctx.input<std_msgs::Float64>("a")->data + b));
  }
};

// Score with a known optimum: -(x - peak)^2; no output when x is outside [valid_from, valid_to].
class Parabola : public Block {
 public:
  Parabola() {
    addInput<std_msgs::Float64>("x", "the tuned value");
    addOutput<std_msgs::Float64>("score", "-(x - peak)^2");
    addProperty<double>("peak", 0.0, "location of the maximum").range(-1e6, 1e6);
    addProperty<double>("valid_from", -1e6, "no score below").range(-1e6, 1e6);
    addProperty<double>("valid_to", 1e6, "no score above").range(-1e6, 1e6);
  }
  void process(Context& ctx) override {
    count(ctx);
    double x = ctx.input<std_msgs::Float64>("x")->data;
    if (x < ctx.property<double>("valid_from") || x > ctx.property<double>("valid_to")) return;
    double d = x - ctx.property<double>("peak");
    ctx.output("score", number(-d * d));
  }
};

// Waits until `parties` Barrier blocks are inside process() at the same time; fails after a
// timeout. Passing proves the executor ran them in parallel (no timing involved).
class Barrier : public Block {
 public:
  Barrier() {
    addOutput<std_msgs::Float64>("value", "1 once all parties met");
    addOptionalInput<std_msgs::Float64>("in", "ignored; lets a barrier sit inside a sub-net");
    addProperty<int>("parties", 2, "how many must meet").range(1, 64);
    addProperty<double>("timeout", 10.0, "seconds to wait before failing").range(0, 600);
    addProperty<std::string>("group", "default", "barriers with the same group meet");
  }
  void process(Context& ctx) override {
    count(ctx);
    static std::mutex m;
    static std::condition_variable cv;
    static std::map<std::string, int> arrived;
    std::unique_lock<std::mutex> lock(m);
    const std::string group = ctx.property<std::string>("group");
    const int parties = ctx.property<int>("parties");
    ++arrived[group];
    cv.notify_all();
    bool met = cv.wait_for(lock, std::chrono::duration<double>(ctx.property<double>("timeout")),
                           [&] { return arrived[group] >= parties; });
    if (!met) {
      --arrived[group];
      throw BlockError("barrier '" + group + "': only " + std::to_string(arrived[group] + 1) + " of " +
                       std::to_string(parties) + " blocks arrived");
    }
    ctx.output("value", number(1.0));
  }
};

// Outputs how many times this instance ran (1, 2, 3, ...): tells repetitions apart.
class Counter : public Block {
 public:
  Counter() {
    addOutput<std_msgs::Float64>("count", "runs so far, this one included");
    addProperty<int>("fail_every", 0, "fail every n-th run (0 = never): a flaky measurement").range(0, 1000);
  }
  void process(Context& ctx) override {
    count(ctx);
    const int run = ++runs_;
    const int fail_every = ctx.property<int>("fail_every");
    if (fail_every > 0 && run % fail_every == 0) throw BlockError("run " + std::to_string(run) + " failed on purpose");
    ctx.output("count", number(static_cast<double>(run)));
  }

 private:
  std::atomic<int> runs_{0};  // test-only state across runs
};

// Whether the numbers add up to at least `threshold`: a stop condition (a sub-net's until net).
class SumAtLeast : public Block {
 public:
  SumAtLeast() {
    addInput<std_msgs::Float64MultiArray>("values", "numbers");
    addInput<std_msgs::Float64>("threshold", "the sum to reach");
    addOutput<std_msgs::Bool>("reached", "sum(values) >= threshold");
  }
  void process(Context& ctx) override {
    count(ctx);
    const auto values = ctx.input<std_msgs::Float64MultiArray>("values");
    const double threshold = ctx.input<std_msgs::Float64>("threshold")->data;
    if (threshold < 0) throw BlockError("input 'threshold': " + std::to_string(threshold) + " is below 0");
    auto reached = boost::make_shared<std_msgs::Bool>();
    reached->data = std::accumulate(values->data.begin(), values->data.end(), 0.0) >= threshold;
    ctx.output("reached", reached);
  }
};

}  // namespace

int calls(const std::string& block_name) {
  std::lock_guard<std::mutex> lock(calls_mutex);
  auto it = call_counts.find(block_name);
  return it == call_counts.end() ? 0 : it->second;
}

void resetCalls() {
  std::lock_guard<std::mutex> lock(calls_mutex);
  call_counts.clear();
}

}  // namespace test
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::Constant, "test/Constant", "test", "Outputs a number");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::Scale, "test/Scale", "test", "in * gain + offset");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::Add, "test/Add", "test", "a + b");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::Parabola, "test/Parabola", "test", "Score with a known peak");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::Counter, "test/Counter", "test", "Counts its runs");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::SumAtLeast, "test/SumAtLeast", "test", "sum(values) >= threshold (fails below 0)");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::test::Barrier, "test/Barrier", "test", "Meets other barriers");
