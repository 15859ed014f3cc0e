// SPDX-License-Identifier: MIT
// Progress and dry-run lines: the numbers they print are the ones computed.
#include <catch2/catch.hpp>

#include "platform/eval/progress_line.hpp"

using namespace smi::eval;

TEST_CASE("durations print as s, m:ss and h:mm:ss") {
  CHECK(format_duration(0.35) == "0.35 s");
  CHECK(format_duration(12.4) == "12 s");
  CHECK(format_duration(62) == "1:02");
  CHECK(format_duration(3723) == "1:02:03");
  CHECK(format_duration(-1) == "?");
}

TEST_CASE("progress and plan lines carry counts, mean and ETA") {
  Progress p;
  p.total = 40; p.done = 12; p.failed = 1; p.running = 2; p.mean_seconds = 1.3; p.eta_seconds = 40;
  CHECK(format_progress("column", p) == "column: 12/40 runs done, 1 failed, 2 running, mean 1.3 s, ETA 40 s");
  Plan pl;
  pl.points = 40; pl.unique = 40; pl.reused = 12; pl.runs = 28; pl.timing = {31, 27.0};
  pl.eta_seconds = 28 * 27.0 / 2;
  CHECK(format_plan("column", pl, 2) ==
        "dry run: model 'column' would launch 28 solver runs for 40 points (12 found in the store); "
        "ETA 6:18 at concurrency 2 from 31 stored runs (mean 27 s)");
  pl.timing = {};
  CHECK_THAT(format_plan("column", pl, 2), Catch::EndsWith("ETA unknown (no stored run of this program and version)"));
}
