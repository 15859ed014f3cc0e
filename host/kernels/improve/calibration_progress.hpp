// SPDX-License-Identifier: MIT
#pragma once
// Turns a calibration's evaluations into progress rows: which stage, how many
// of its units are done, the evaluations, the best objective and an ETA from the rate so far.
// Thread-safe (starts optimised side by side report from several threads); rows are throttled
// to ten a second, the final row always goes out.
#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/calibration.hpp"

namespace smi::improve {

class ProgressTracker {
 public:
  /// `units` of the stage (starts, replicates, evaluations), `budget` evaluations at most for the
  /// whole stage (0: unknown; then the ETA comes from the units).
  ProgressTracker(ProgressLine line, std::string stage, int units, long budget);
  /// An optimiser's evaluation of start `start` (0-based).
  void evaluation(const HistoryEntry& h);
  /// A unit done (a replicate), with the stage's evaluations so far.
  void unit_done(int done, long evaluations);
  /// One evaluation of a stage counted in evaluations (the near-optimal analysis).
  void count();
  /// The stage's last line (a newline on the terminal).
  void finish();

 private:
  void show(bool final);  // with mu_ held

  ProgressLine line_;
  std::string stage_;
  int units_;
  long budget_;
  std::mutex mu_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
  long evaluations_ = 0;
  long evaluations_at_done_ = 0;  ///< evaluations when the last unit ended (the optimiser's starts)
  int done_ = 0;
  int highest_start_ = 0;
  double best_ = 0.0;
  bool has_best_ = false;
  bool finished_ = false;
};

}  // namespace smi::improve
