// SPDX-License-Identifier: MIT
#include "kernels/improve/calibration_progress.hpp"

#include <algorithm>
#include <cmath>

namespace smi::improve {

ProgressTracker::ProgressTracker(ProgressLine line, std::string stage, int units, long budget)
    : line_(std::move(line)), stage_(std::move(stage)), units_(units), budget_(budget) {}

void ProgressTracker::evaluation(const HistoryEntry& h) {
  std::lock_guard<std::mutex> lock(mu_);
  ++evaluations_;
  if (!h.probe && std::isfinite(h.value) && (!has_best_ || h.value < best_)) {
    best_ = h.value;
    has_best_ = true;
  }
  // Starts run in order (or side by side, each thread in order): a start above the highest seen
  // means the ones below it have ended.
  highest_start_ = std::max(highest_start_, h.start);
  if (highest_start_ > done_) {
    done_ = highest_start_;
    evaluations_at_done_ = evaluations_ - 1;  // this evaluation belongs to the next start
  }
  show(false);
}

void ProgressTracker::unit_done(int done, long evaluations) {
  std::lock_guard<std::mutex> lock(mu_);
  done_ = done;
  evaluations_ = evaluations;
  show(done >= units_);
  if (done >= units_) finished_ = true;
}

void ProgressTracker::count() {
  std::lock_guard<std::mutex> lock(mu_);
  ++evaluations_;
  done_ = static_cast<int>(std::min<long>(evaluations_, units_));
  show(false);
}

void ProgressTracker::finish() {
  std::lock_guard<std::mutex> lock(mu_);
  if (finished_) return;
  finished_ = true;
  done_ = units_;
  show(true);
}

void ProgressTracker::show(bool final) {
  if (!line_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!final && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  ProgressRow row;
  row.stage = stage_;
  row.done = done_;
  row.total = units_;
  row.evaluations = evaluations_;
  row.best = has_best_ ? best_ : std::nan("");
  row.final = final;
  // The rate so far times what is left: of the budget while no unit has ended (an upper bound),
  // else of the units at the evaluations per unit seen.
  if (final) {
    row.eta = 0.0;
  } else if (evaluations_ > 0 && done_ > 0 && units_ > 0 && evaluations_at_done_ > 0) {
    // the units ended so far took evaluations_at_done_ evaluations; those left take as many each,
    // less what the running one has done (at least a tenth of a unit: it may run long)
    const double per_unit = static_cast<double>(evaluations_at_done_) / static_cast<double>(done_);
    const double left = std::max(0.1 * per_unit, per_unit * static_cast<double>(units_ - done_) -
                                                     static_cast<double>(evaluations_ - evaluations_at_done_));
    row.eta = elapsed / static_cast<double>(evaluations_) * left;
  } else if (evaluations_ > 0 && done_ > 0 && units_ > 0) {
    row.eta = elapsed * static_cast<double>(units_ - done_) / static_cast<double>(done_);
  } else if (evaluations_ > 0 && budget_ > 0) {
    row.eta = elapsed * static_cast<double>(std::max(0L, budget_ - evaluations_)) / static_cast<double>(evaluations_);
  }
  line_(row);
}

}  // namespace smi::improve
