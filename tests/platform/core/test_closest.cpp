// SPDX-License-Identifier: MIT
// The one suggestion logic (platform/core/closest.hpp) of member names, doc names and options.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "platform/core/closest.hpp"

TEST_CASE("name distance ignores case and counts neighbour swaps once") {
  CHECK(smi::name_distance("Normal", "normal") == 0);
  CHECK(smi::name_distance("kdee", "kde") == 1);
  CHECK(smi::name_distance("nromal", "normal") == 1);
  CHECK(smi::name_distance("", "abc") == 3);
}

TEST_CASE("closest names, nearest first") {
  const std::vector<std::string> names = {"smi.kde", "smi.kde_bd", "smi.doe", "smi.calibrate"};
  const auto near = smi::closest("smi.kdee", names);
  REQUIRE(!near.empty());
  CHECK(near[0] == "smi.kde");
  CHECK(smi::closest("calibrate", names) == std::vector<std::string>{"smi.calibrate"});  // the part after '.'
  CHECK(smi::closest("zzzzzz", names).empty());
}
