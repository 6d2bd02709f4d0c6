// The executor runs a net in one process (paper 3.1): event flow, independent blocks in parallel
// on a thread pool, and re-execution of only what is out of date. It is also the C++ embedding
// API: no GUI and no ROS master needed.
//
//   auto exec = imagenets::Executor::loadFile("threshold_demo.yaml");
//   exec->run();
//   auto binary = exec->output<sensor_msgs::Image>("threshold.image");
//   exec->setProperty("threshold", "threshold", 72);
//   exec->run();  // re-runs `threshold` and what is downstream of it, nothing else
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "imagenets/net.h"
#include "imagenets/run_events.h"
#include "imagenets/package_file.h"

namespace imagenets {

class FeedbackSearch;
class ThreadPool;

struct RunReport {
  std::vector<std::string> ran;     // blocks that ran, in completion order
  std::vector<std::string> failed;  // "block: message"
  std::vector<std::string> not_run; // "block: reason"
  bool cancelled = false;           // cancel() stopped the run; the blocks not reached stay out of date
  bool ok() const { return failed.empty(); }
};

struct ExecutorOptions {
  int threads = 0;  // 0 = number of cores
  // Measure each block's CPU time (BlockStats::last_cpu_ms) also when no observer watches the runs
  // (with one it always is): two system calls per block, about 1 us.
  bool cpu_time = false;
};

class Executor {
 public:
  explicit Executor(std::unique_ptr<Net> net, ExecutorOptions options = {});
  static std::unique_ptr<Executor> loadFile(const std::string& path, ExecutorOptions options = {});
  ~Executor();
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  const Net& net() const { return *net_; }
  int threads() const;

  // Runs every out-of-date block (all of them the first time), in event flow.
  RunReport run();
  // Re-runs one block and what is downstream of it.
  RunReport runBlock(const std::string& block);
  // Runs one block only, on the values its inputs hold now (paper 3.2: "execute only single
  // blocks"). Its downstream is marked out of date, not run: the next run() refreshes it, and the
  // block itself too while a block above it is out of date. A block with feedback runs its sweep
  // (the blocks between it and its score are part of it). Throws NetError for an unknown block.
  RunReport runBlockOnly(const std::string& block);
  // Runs every block again, sources included (e.g. one more loop of a repeated sub-net).
  RunReport runAll();

  // Feeds an input port that no link feeds ("block.port"); marks the block out of date.
  void setInput(const std::string& block_port, const Value& value);
  template <class M>
  void setInput(const std::string& block_port, const boost::shared_ptr<const M>& msg) {
    setInput(block_port, PortType::of<M>().wrap(msg));
  }

  // What setProperties did.
  enum class PropertyChange {
    Applied,       // the block has the new values (configured anew), out of date
    NeedsRebuild,  // the values change the block's ports: nothing changed; build the net anew
  };
  // Sets several properties of one block at once, all or none. A changed value gives a new instance
  // of the block, configured with the new values, so what configure() reads (a sub-net's net, a
  // marker file) takes effect as at load; its ports must stay, since links are wired to them. Marks
  // the block out of date so the next run re-executes it and its downstream. Throws NetError
  // "<origin>: block 'b': <why>" (no such block, unknown property, invalid value, refused by
  // configure()), changing nothing.
  PropertyChange setProperties(const std::string& block, const PropertyValues& values);
  // One property; NetError too when the value would change the block's ports.
  void setProperty(const std::string& block, const std::string& property, const PropertyValue& value);
  // A written value ("72", "[1, 2]"; relative paths against the working directory).
  void setPropertyText(const std::string& block, const std::string& property, const std::string& text);
  // Marks a block out of date without changing it (e.g. the net inside a sub-net block changed):
  // the next run re-executes it and its downstream. Throws NetError for an unknown block.
  void markOutOfDate(const std::string& block);

  // The cached value of an output port ("block.port"); empty if it has none.
  Value output(const std::string& block_port) const;
  template <class M>
  boost::shared_ptr<const M> output(const std::string& block_port) const {
    return output(block_port).as<M>();
  }
  BlockStats stats(const std::string& block) const;

  // Run events (run_events.h): block started / finished / cached, feedback trial, sub-net
  // repetition, run finished. Returns an id for removeObserver. Thread-safe.
  int addObserver(RunObserver observer);
  void removeObserver(int id);
  // Stops the run in progress (thread-safe, from any thread; a no-op when idle): no block, feedback
  // trial or sub-net repetition starts after it. Blocks not reached are NotRun ("cancelled") and
  // stay out of date, so the next run() continues where this one stopped; the run returns a report
  // with `cancelled` set. The executor stays usable.
  void cancel();
  // Makes this executor's runs part of an outer run, until called again with an empty channel:
  // its events (but RunFinished) also go to `outer.emit`, and `outer.cancelled` cancels it too. A
  // block that runs a net inside passes its Context's innerChannel() for the length of process().
  void nestIn(RunChannel outer);

 private:
  using Store = std::vector<std::vector<Value>>;        // per node, per output port
  using Overrides = std::map<int, PropertyValues>;     // property values for one trial
  // Who waits for whom among the units of one execute() call (a unit: a block, or a feedback
  // block with its region); built once per set of nodes, not per run.
  struct Schedule {
    std::vector<int> units;                    // in topological order
    std::vector<size_t> providers;             // per node: how many units of the set feed it
    std::vector<std::vector<int>> dependents;  // per node: the units it feeds
  };
  Schedule plan(const std::vector<int>& nodes, bool trial) const;

  void markOutOfDate(int node);
  int nodeIndex(const std::string& block) const;  // NetError "<origin>: no block named 'x'"
  // The node's block configured anew with `changes` (NetError naming it when refused).
  std::unique_ptr<Block> reconfigured(int node, const PropertyValues& changes) const;
  // Starts a public run: clears the cancel flag and the cancelled blocks of the last run.
  void beginRun();
  // The report's `cancelled`: a block of this run was cancelled.
  bool anyUnfinished() const;
  RunReport runOutOfDate();
  // Runs the schedule's units in event flow against `store`: a unit starts when the units that
  // feed it are done; independent units run in parallel. Nodes outside the set keep their outputs.
  // The core of run(), and of every feedback trial (with `overrides`, into a copy of the store).
  void execute(const Schedule& schedule, Store& store, RunReport& report, const Overrides* overrides);
  void runUnit(int unit, Store& store, RunReport& report, const Overrides* overrides);
  void runNode(int node, Store& store, RunReport& report, const Overrides* overrides);
  // Feedback (paper 3.4): sweeps the node's property over its candidates, each trial running the
  // region between the node and its score; keeps the best trial's outputs in `store`.
  void runFeedback(int node, Store& store, RunReport& report);
  // The steps of runFeedback: the region skipped for a missing input; the trials (returns the best
  // trial's store); one trial's event; the trace output; the best trial's outputs kept (or none).
  void skipFeedbackRegion(int node, const std::string& missing, Store& store, RunReport& report);
  Store sweep(int node, FeedbackSearch& search, const Store& store);
  void emitTrial(int node, const FeedbackSearch& search);
  Value feedbackTrace(int node, const FeedbackSearch& search) const;
  void keepBestTrial(int node, const FeedbackSearch& search, Store best_store, Store& store, RunReport& report);
  double runTrial(int node, double candidate, const Store& base, Store& trial_store);
  std::vector<double> initialCandidates(int node, const Store& store) const;
  // Runs task(0..count-1) on the pool (the calling thread helps) and returns when all are done.
  void runParallel(size_t count, const std::function<void(size_t)>& task);
  std::vector<Value> gatherInputs(int node, const Store& store) const;
  // "input 'x' has no value (block 'b' produced none)" / "(not linked, not set)".
  std::string explainMissing(int node, int input) const;
  BlockStats statsOf(int node) const;
  // Records a block's status; `counted` adds a process() call to its timings (cpu_ms NaN: not
  // measured).
  void record(int node, BlockStatus status, const std::string& message, double ms, bool counted,
              double cpu_ms = std::numeric_limits<double>::quiet_NaN());
  // record() + a BlockFinished event.
  void finish(int node, BlockStatus status, const std::string& message, double ms, bool counted,
              double cpu_ms = std::numeric_limits<double>::quiet_NaN());
  // A unit (a block, or a feedback block with its region) that a cancel kept from starting.
  void skipCancelled(int unit, RunReport& report);
  bool cancelled() const;
  bool watched() const;  // someone listens to events (else they are not even built)
  void emit(const RunEvent& event);
  void emitBlockEvent(RunEventKind kind, int node, const BlockStats& stats);
  // Ends a public run: clears the running state and tells the observers (outside mutex_).
  RunReport finishRun(RunReport report);

  std::unique_ptr<Net> net_;
  const bool cpu_time_;
  std::unique_ptr<ThreadPool> pool_;
  mutable std::mutex mutex_;  // serialises the public API
  Store outputs_;
  std::vector<std::vector<Value>> external_inputs_;
  std::vector<bool> out_of_date_;
  std::vector<std::vector<int>> feedback_region_;  // per node with feedback: itself + path to the score
  std::vector<int> absorbed_by_;                   // node -> the feedback node whose region holds it, or -1
  std::vector<Schedule> trial_schedule_;           // per node with feedback: its region's
  std::vector<int> scheduled_nodes_;               // the node set of run_schedule_ (mutex_ held)
  Schedule run_schedule_;
  mutable std::mutex stats_mutex_;
  std::vector<BlockStats> stats_;
  std::mutex report_mutex_;

  std::mutex observers_mutex_;
  std::map<int, RunObserver> observers_;
  int next_observer_ = 0;
  std::atomic<int> observer_count_{0};
  RunChannel outer_;                  // set by nestIn(), read during runs (mutex_ held)
  std::atomic<bool> running_{false};
  std::atomic<bool> cancel_{false};
  std::vector<char> unfinished_;      // per node: cancelled in the current run (stays out of date)
};

}  // namespace imagenets
