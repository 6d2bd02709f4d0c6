// Which candidates a feedback search tries, in what order, and why it stops (paper 3.4,
// generalised). Pure logic: no blocks, no threads. The executor asks for the next batch, runs its
// trials (in parallel or one by one) and reports their scores back in batch order; the search
// decides only from the reported scores, so parallel and sequential runs try the same candidates
// in the same order and choose the same one.
//
//   FeedbackSearch search(spec, {otsu_value});
//   for (auto batch = search.nextBatch(); !batch.empty(); batch = search.nextBatch())
//     for (double v : batch) if (!search.report(score(v))) break;   // false: good enough, stop
//   search.best();  // index into search.trials(), -1 if no candidate had a score
//
// Strategies (FeedbackSpec): the `initial` candidates first (one batch), then
// - exhaustive: every candidate (one batch);
// - coarse_to_fine with `coarse_step` and `fine_radius`: the grid from, from +- coarse_step, ...
//   towards to (one batch), then centre +- k * step for k = 1 .. fine_radius / step around the
//   best so far, within from..to (one batch);
// - coarse_to_fine without them: a grid of about sqrt(N) candidates, then halving the spacing
//   around the best (two candidates per batch); everything if the grid finds no score.
// A score that is NaN or infinite is invalid. The best is the highest (minimize: lowest) valid
// score; on a tie the candidate tried first wins. With `good_enough` the search stops at the
// first candidate, in the order tried, whose score reaches it.
#pragma once

#include <functional>
#include <vector>

#include "imagenets/net.h"

namespace imagenets {

class FeedbackSearch {
 public:
  enum class Stop { Running, AllTried, GoodEnough, Finished, Cancelled };
  static const char* stopName(Stop stop);  // "all_tried", "good_enough", "finished", "cancelled"

  struct Trial {
    double value;
    double score;  // NaN: invalid
  };

  // `initial`: the first candidates, in order (the spec's constants and port values resolved by
  // the caller; non-finite ones are skipped). `normalise`: the value the property really takes
  // (an int property rounds); identity when empty. A value already tried is not tried again.
  FeedbackSearch(const FeedbackSpec& spec, std::vector<double> initial,
                 std::function<double(double)> normalise = {});

  // The candidates to try next, in order; empty once the search is over. Report each (in this
  // order) until report() returns false before asking for the next batch.
  std::vector<double> nextBatch();
  // The score of the next candidate of the current batch. Returns false when the search stops
  // here (good enough): the rest of the batch is not needed.
  bool report(double score);
  // Stops the search (the caller was cancelled); the trials so far stay recorded.
  void cancel();

  Stop stop() const { return stop_; }
  bool finished() const { return stop_ != Stop::Running; }
  const std::vector<Trial>& trials() const { return trials_; }
  int best() const { return best_; }
  size_t candidates() const { return values_.size(); }

 private:
  enum class Phase { Initial, Main, Fine, HalvingAfterGrid, HalvingStep, HalvingLast, DoneAll, DoneFinished };

  std::vector<double> plan();  // the next batch of the current phase (maybe empty); advances the phase
  bool tried(double value) const;
  bool better(double score, double than) const;
  int nearestIndex(double value) const;
  std::vector<double> atIndices(std::vector<int> indices) const;

  const FeedbackSpec spec_;
  std::vector<double> values_;   // the declared candidates, normalised
  std::vector<double> initial_;
  std::function<double(double)> normalise_;
  Phase phase_ = Phase::Initial;
  Stop stop_ = Stop::Running;
  int spacing_ = 0;              // halving search: current index spacing
  std::vector<double> pending_;  // the current batch
  size_t next_ = 0;              // its next candidate to report
  std::vector<Trial> trials_;
  int best_ = -1;
};

}  // namespace imagenets
