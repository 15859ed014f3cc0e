// SPDX-License-Identifier: MIT
// The calibration's progress line: the rows the kernel's tracker makes (stage,
// units done, evaluations, best, ETA from the rate so far) and the text the terminal shows, the
// solver runs' show_progress/format_duration reused. Whether it shows (a terminal, not --quiet,
// progress ~= false) is the binding's; the tests below need no terminal.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "bindings/improve/progress_line.hpp"
#include "kernels/improve/calibration_progress.hpp"

using namespace smi::improve;

TEST_CASE("progress rows: starts done, evaluations, best objective, ETA; the last row is final") {
  std::vector<ProgressRow> rows;
  ProgressTracker t([&](const ProgressRow& r) { rows.push_back(r); }, "calibration", 4, 4 * 300);
  HistoryEntry h;
  h.theta = Eigen::VectorXd::Zero(1);
  h.value = 0.5;
  t.evaluation(h);  // the first row always shows
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].done == 0);
  CHECK(rows[0].evaluations == 1);
  CHECK(rows[0].best == 0.5);
  CHECK(rows[0].eta >= 0.0);  // from the budget: 1199 evaluations left at the rate so far
  std::this_thread::sleep_for(std::chrono::milliseconds(120));
  h.start = 2;  // starts 1 and 2 have ended
  h.value = 0.25;
  t.evaluation(h);
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].done == 2);
  CHECK(rows[1].best == 0.25);
  h.value = 0.75;
  h.probe = true;  // probes count as evaluations, never as the best
  t.evaluation(h);
  t.finish();
  CHECK(rows.back().final);
  CHECK(rows.back().done == 4);
  CHECK(rows.back().evaluations == 3);
  CHECK(rows.back().best == 0.25);
  const std::size_t n = rows.size();
  t.finish();  // once only
  CHECK(rows.size() == n);
}

TEST_CASE("progress text: one line per stage, ETA by the solver line's format_duration") {
  using smi::bind::improve::format_progress_row;
  ProgressRow r;
  r.stage = "calibration";
  r.done = 1;
  r.total = 4;
  r.evaluations = 137;
  r.best = 0.28812345;
  r.eta = 42.0;
  CHECK(format_progress_row(r) == "calibration: start 2/4, 137 evaluations, best 0.288123, ETA 42 s");
  r.stage = "bootstrap";
  r.done = 12;
  r.total = 100;
  r.evaluations = 1234;
  r.best = std::nan("");
  r.eta = 190.0;
  CHECK(format_progress_row(r) == "bootstrap: 12/100 replicates, 1234 evaluations, ETA 3:10");
  r.stage = "near-optimal";
  r.final = true;
  CHECK(format_progress_row(r) == "near-optimal: 1234 evaluations, done");
}
