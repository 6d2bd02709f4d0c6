#include "imagenets/run_events.h"

#include <cmath>
#include <cstdio>

namespace imagenets {

const char* statusName(BlockStatus status) {
  switch (status) {
    case BlockStatus::Pending: return "pending";
    case BlockStatus::Ok: return "ok";
    case BlockStatus::Failed: return "failed";
    case BlockStatus::NotRun: return "not run";
  }
  return "?";
}

const char* eventName(RunEventKind kind) {
  switch (kind) {
    case RunEventKind::BlockStarted: return "started";
    case RunEventKind::BlockFinished: return "finished";
    case RunEventKind::BlockCached: return "cached";
    case RunEventKind::FeedbackTrial: return "feedback trial";
    case RunEventKind::Repetition: return "repetition";
    case RunEventKind::RunFinished: return "run finished";
  }
  return "?";
}

void BlockStats::record(BlockStatus new_status, const std::string& new_message, double ms, bool processed,
                        double cpu_ms) {
  status = new_status;
  message = new_message;
  // last_error goes with `failures`: what process() said, not a verdict about the block (e.g. a
  // feedback's "no valid candidate" after trials that failed keeps the trials' reason).
  if (status == BlockStatus::Failed && processed) {
    last_error = message;
    ++failures;
  }
  if (processed) {
    ++runs;
    last_ms = ms;
    mean_ms += (ms - mean_ms) / static_cast<double>(runs);
  }
  if (processed && !std::isnan(cpu_ms)) {
    ++cpu_runs;
    last_cpu_ms = cpu_ms;
    mean_cpu_ms += (cpu_ms - mean_cpu_ms) / static_cast<double>(cpu_runs);
  }
}

std::string describe(const RunEvent& e) {
  char number[64];
  std::string text = e.block.empty() ? std::string() : e.block + ": ";
  switch (e.kind) {
    case RunEventKind::BlockStarted:
      return text + "started";
    case RunEventKind::BlockFinished:
      text += statusName(e.stats.status);
      if (e.stats.status == BlockStatus::Ok) {
        std::snprintf(number, sizeof number, " (%.3f ms, CPU %.3f ms)", e.stats.last_ms, e.stats.last_cpu_ms);
        text += number;
      }
      return e.stats.message.empty() ? text : text + ": " + e.stats.message;
    case RunEventKind::BlockCached:
      return text + "cached";
    case RunEventKind::FeedbackTrial:
      std::snprintf(number, sizeof number, " = %g -> score %g", e.value, e.score);
      return text + "feedback trial " + std::to_string(e.index) + " of " + std::to_string(e.count) + ": " +
             e.message + number;
    case RunEventKind::Repetition:
      text += "repetition " + std::to_string(e.index) + " of " + std::to_string(e.count) + " done";
      return e.message.empty() ? text : text + " (" + e.message + ")";
    case RunEventKind::RunFinished:
      return text + (e.message.empty() ? "run finished" : "run " + e.message);
  }
  return text;
}

}  // namespace imagenets
