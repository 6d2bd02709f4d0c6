// Run events and cancel: the one observer API through which every host watches a run (the nodelet
// host's ~status, `imagenets run`'s progress lines, the calibration action's feedback, the
// Designer). Events come from the executor; a block that runs something inside (a sub-net) passes
// its inner events on through its Context, so observers of the outer executor see them too.
//
//   exec->addObserver([](const imagenets::RunEvent& e) {
//     if (e.kind == imagenets::RunEventKind::BlockFinished) std::cout << e.block << " " << e.stats.last_ms;
//   });
//   std::thread t([&] { exec->run(); });
//   exec->cancel();   // from any thread: the run stops between blocks / trials / repetitions
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>

namespace imagenets {

enum class BlockStatus { Pending, Ok, Failed, NotRun };
const char* statusName(BlockStatus status);

// One stats type for every host (executor, nodelet host, test harness): what the invocations of
// a block did.
struct BlockStats {
  BlockStatus status = BlockStatus::Pending;
  std::string message;     // why it failed or did not run
  size_t runs = 0;         // completed process() calls, failed ones included (feedback trials too)
  size_t failures = 0;     // process() calls that failed
  double last_ms = 0.0;
  double mean_ms = 0.0;
  // CPU time of the thread that ran process(): what the block cost, whatever else the machine
  // did meanwhile. Work it handed to other threads (parallel feedback trials, a sub-net with
  // more than one thread) is not in it.
  // Measured only when shown (an executor with an observer, or ExecutorOptions::cpu_time):
  // cpu_runs counts the calls that were.
  double last_cpu_ms = 0.0;
  double mean_cpu_ms = 0.0;
  size_t cpu_runs = 0;
  std::string last_error;  // the last failed process() call's message, kept after later successes

  // Records one invocation; `processed`: process() was called (it counts as a run, timed);
  // `cpu_ms` NaN: not measured.
  void record(BlockStatus new_status, const std::string& new_message, double ms, bool processed,
              double cpu_ms = std::numeric_limits<double>::quiet_NaN());
};

enum class RunEventKind {
  BlockStarted,   // process() is about to be called (not sent for feedback trials' inner runs)
  BlockFinished,  // the block ran, failed or was not run: `stats` says which and why
  BlockCached,    // the run did not need the block: its outputs are still valid (served from cache)
  FeedbackTrial,  // one candidate of a feedback search was scored: `value`, `score`, `index` of `count`
  Repetition,     // a repeated sub-net finished repetition `index` (1-based) of `count`
  RunFinished,    // run()/runBlock()/runAll() returned (`message`: "cancelled" when it was)
};
const char* eventName(RunEventKind kind);

struct RunEvent {
  RunEventKind kind = RunEventKind::BlockFinished;
  // The block's name in the observed executor's net. Events of blocks inside a sub-net carry the
  // path "outer/inner" (any depth), so one observer sees the whole hierarchy.
  std::string block;
  // BlockFinished, BlockCached: the block's stats after the event; Repetition: only `status` (ok or
  // failed) and, when it failed, `message` (why): test these, not the text of `message` below.
  BlockStats stats;
  // FeedbackTrial: the tuned property; Repetition: for people, "failed: ..." if it failed, and
  // what an until net answered after it ("until net: not done").
  std::string message;
  double value = std::numeric_limits<double>::quiet_NaN();  // FeedbackTrial: the candidate tried
  double score = std::numeric_limits<double>::quiet_NaN();  // FeedbackTrial: its score (NaN: invalid)
  int index = 0;  // FeedbackTrial: trials done so far; Repetition: the repetition just done (1-based)
  int count = 0;  // FeedbackTrial: the number of candidates; Repetition: N
};

// One line for people: "threshold: ok (1.234 ms, CPU 1.200 ms)", "loop: repetition 2 of 5 done",
// "threshold: feedback trial 3 of 41: threshold = 90 -> score 0.75".
std::string describe(const RunEvent& event);

// Called on the thread that produced the event (a pool thread, possibly several at once): an
// observer must be thread-safe and quick, and must not call back into the executor that sends it.
using RunObserver = std::function<void(const RunEvent&)>;

// What a run offers the blocks it runs (through their Context): where their own events go and
// whether the run was cancelled. Either part may be empty (nobody listens / cannot be cancelled).
struct RunChannel {
  RunObserver emit;
  std::function<bool()> cancelled;
};

}  // namespace imagenets
