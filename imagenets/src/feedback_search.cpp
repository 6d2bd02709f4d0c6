#include "feedback_search.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imagenets {

namespace {
// Candidates computed as centre + k * step may differ from from + i * step in the last bits.
bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); }
}  // namespace

const char* FeedbackSearch::stopName(Stop stop) {
  switch (stop) {
    case Stop::Running: return "running";
    case Stop::AllTried: return "all_tried";
    case Stop::GoodEnough: return "good_enough";
    case Stop::Finished: return "finished";
    case Stop::Cancelled: return "cancelled";
  }
  return "?";
}

FeedbackSearch::FeedbackSearch(const FeedbackSpec& spec, std::vector<double> initial,
                               std::function<double(double)> normalise)
    : spec_(spec), normalise_(normalise ? std::move(normalise) : [](double v) { return v; }) {
  for (double v : spec_.values) values_.push_back(normalise_(v));
  for (double v : initial) {
    if (std::isfinite(v)) initial_.push_back(normalise_(v));
  }
}

bool FeedbackSearch::tried(double value) const {
  return std::any_of(trials_.begin(), trials_.end(), [&](const Trial& t) { return same(t.value, value); });
}

bool FeedbackSearch::better(double score, double than) const {
  return spec_.maximize ? score > than : score < than;
}

int FeedbackSearch::nearestIndex(double value) const {
  int nearest = 0;
  for (size_t i = 1; i < values_.size(); ++i) {
    if (std::abs(values_[i] - value) < std::abs(values_[nearest] - value)) nearest = static_cast<int>(i);
  }
  return nearest;
}

std::vector<double> FeedbackSearch::atIndices(std::vector<int> indices) const {
  std::sort(indices.begin(), indices.end());
  std::vector<double> out;
  for (int i : indices) {
    if (i >= 0 && i < static_cast<int>(values_.size())) out.push_back(values_[i]);
  }
  return out;
}

std::vector<double> FeedbackSearch::nextBatch() {
  if (next_ < pending_.size() && stop_ == Stop::Running) {
    throw std::logic_error("FeedbackSearch: " + std::to_string(pending_.size() - next_) +
                           " candidates of the current batch were not reported");
  }
  while (stop_ == Stop::Running) {
    std::vector<double> batch;
    for (double v : plan()) {
      const bool repeated = std::any_of(batch.begin(), batch.end(), [&](double b) { return same(b, v); });
      if (!repeated && !tried(v)) batch.push_back(v);
    }
    if (!batch.empty()) {
      pending_ = std::move(batch);
      next_ = 0;
      return pending_;
    }
  }
  pending_.clear();
  next_ = 0;
  return {};
}

std::vector<double> FeedbackSearch::plan() {
  const int count = static_cast<int>(values_.size());
  const bool explicit_grid = spec_.coarse_step.has_value();
  switch (phase_) {
    case Phase::Initial:
      phase_ = Phase::Main;
      return initial_;
    case Phase::Main:
      if (spec_.search != "coarse_to_fine" || (!explicit_grid && count <= 3)) {
        phase_ = Phase::DoneAll;
        return values_;
      }
      if (explicit_grid) {
        // The grid from `from` towards `to` in coarse steps; `to` itself only when it lies on the grid.
        phase_ = Phase::Fine;
        std::vector<double> grid;
        const double from = *spec_.from, to = *spec_.to, step = to < from ? -*spec_.coarse_step : *spec_.coarse_step;
        const auto n = static_cast<long>(std::floor((to - from) / step + 1e-9));
        for (long k = 0; k <= n; ++k) grid.push_back(normalise_(from + step * static_cast<double>(k)));
        return grid;
      } else {
        // About sqrt(N) evenly spaced candidates and the last one: reaches the optimum of a
        // unimodal score in O(sqrt(N) + log N) trials instead of N.
        spacing_ = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
        std::vector<int> grid;
        for (int i = 0; i < count; i += spacing_) grid.push_back(i);
        grid.push_back(count - 1);
        phase_ = Phase::HalvingAfterGrid;
        return atIndices(grid);
      }
    case Phase::Fine: {
      phase_ = Phase::DoneFinished;
      if (best_ < 0) return {};  // nothing to refine around
      const double centre = trials_[best_].value, step = *spec_.step;
      const double lo = std::min(*spec_.from, *spec_.to), hi = std::max(*spec_.from, *spec_.to);
      const auto k_max = static_cast<long>(std::floor(*spec_.fine_radius / step + 1e-9));
      std::vector<double> fine;
      for (long k = -k_max; k <= k_max; ++k) {
        const double v = centre + step * static_cast<double>(k);
        if (k != 0 && v >= lo - 1e-9 && v <= hi + 1e-9) fine.push_back(normalise_(v));
      }
      return fine;
    }
    case Phase::HalvingAfterGrid:
      if (best_ < 0) {  // the score exists only in a narrow band the grid missed: try everything
        phase_ = Phase::DoneAll;
        return values_;
      }
      phase_ = Phase::HalvingStep;
      return {};
    case Phase::HalvingStep: {
      if (spacing_ <= 1) {
        phase_ = Phase::DoneFinished;
        return {};
      }
      spacing_ = (spacing_ + 1) / 2;
      const int centre = nearestIndex(trials_[best_].value);
      phase_ = spacing_ == 1 ? Phase::HalvingLast : Phase::HalvingStep;
      return atIndices({centre - spacing_, centre + spacing_});
    }
    case Phase::HalvingLast: {
      phase_ = Phase::DoneFinished;
      const int centre = nearestIndex(trials_[best_].value);
      return atIndices({centre - 1, centre + 1});
    }
    case Phase::DoneAll:
      stop_ = Stop::AllTried;
      return {};
    case Phase::DoneFinished:
      stop_ = Stop::Finished;
      return {};
  }
  return {};
}

bool FeedbackSearch::report(double score) {
  if (stop_ != Stop::Running || next_ >= pending_.size()) {
    throw std::logic_error("FeedbackSearch: a score reported with no candidate pending");
  }
  if (!std::isfinite(score)) score = std::nan("");
  trials_.push_back(Trial{pending_[next_++], score});
  if (std::isnan(score)) return true;
  // Strictly better only: on a tie the candidate tried first stays.
  if (best_ < 0 || better(score, trials_[best_].score)) best_ = static_cast<int>(trials_.size()) - 1;
  if (spec_.good_enough && (score == *spec_.good_enough || better(score, *spec_.good_enough))) {
    stop_ = Stop::GoodEnough;
    return false;
  }
  return true;
}

void FeedbackSearch::cancel() {
  if (stop_ == Stop::Running) stop_ = Stop::Cancelled;
}

}  // namespace imagenets
