// SPDX-License-Identifier: MIT
// The run's warning sink (platform/core/run_context.hpp): warnings are kept in order with their
// source, and past WarningSink::kKept only counted, so a warning raised in a long loop bounds
// the memory it takes and still says how many there were.
#include <catch2/catch.hpp>

#include <string>

#include "platform/core/run_context.hpp"

TEST_CASE("warnings are kept in order with their source") {
  smi::WarningSink sink;  // not printing: a test has no terminal
  sink.warn("smi.kde_bd", "3 data point(s) lie outside [0, 1]");
  sink.warn("smi.csv.read", "row 4 repeats row 2");
  const auto w = sink.collected();
  REQUIRE(w.size() == 2);
  CHECK(w[0] == "smi.kde_bd: 3 data point(s) lie outside [0, 1]");
  CHECK(w[1] == "smi.csv.read: row 4 repeats row 2");
}

TEST_CASE("past the kept number, warnings are counted and the count is reported") {
  smi::WarningSink sink;
  const std::size_t n = smi::WarningSink::kKept + 1500;
  for (std::size_t i = 0; i < n; ++i) sink.warn("loop", "warning " + std::to_string(i));
  const auto w = sink.collected();
  REQUIRE(w.size() == smi::WarningSink::kKept + 1);
  CHECK(w.front() == "loop: warning 0");
  CHECK(w[smi::WarningSink::kKept - 1] == "loop: warning " + std::to_string(smi::WarningSink::kKept - 1));
  CHECK(w.back() == "smi-lua: 1500 more warning(s) counted, not kept");
  // A copy (the context is copied into results) keeps both the warnings and the count.
  const smi::WarningSink copy = sink;
  CHECK(copy.collected() == w);
}
