// SPDX-License-Identifier: MIT
// The .f06 parser on the results-file example of docs/spec/steering-column.md §10.
#include <catch2/catch.hpp>
#include <cmath>

#include "platform/eval/f06.hpp"

using namespace smi::eval;

namespace {
const std::string kFixture = std::string(SMI_SOURCE_DIR) + "/tests/solver/fixtures/column_rigid.f06";
}

TEST_CASE("the spec's example results file parses to its printed values") {
  const F06Result r = parse_f06(read_text_file(kFixture), kFixture);
  REQUIRE(r.eigen.size() == 10);
  CHECK(r.eigen[0].mode == 1);
  CHECK(r.eigen[0].eigenvalue == 3.467649E+04);
  CHECK(r.eigen[0].cycles == 2.963724E+01);
  CHECK(r.eigen[3].cycles == 8.023328E+01);
  CHECK(r.eigen[9].mode == 10);
  CHECK(r.eigen[9].order == 10);
  CHECK(r.eigen[9].stiffness == 2.594403E+06);
  for (const auto& e : r.eigen) {
    // The columns are one number three ways: lambda = omega^2, f = omega / 2 pi (6 digits printed).
    CHECK(e.radians * e.radians == Approx(e.eigenvalue).epsilon(2e-6));
    CHECK(e.radians / (2 * M_PI) == Approx(e.cycles).epsilon(2e-6));
    CHECK(e.mass == 1.0);
  }
  REQUIRE(r.labels.size() == 10);
  CHECK(r.labels[2].direction == "TORSION");
  CHECK(r.labels[2].paper == 3);
  CHECK(r.labels[4].paper == 0);  // '-'
  CHECK(r.labels[2].participation[3] == 0.930);
  CHECK(r.labels[9].cycles == r.eigen[9].cycles);
  REQUIRE(r.paper.size() == 4);
  CHECK(r.paper[3].paper == 4);
  CHECK(r.paper[3].direction == "WHEEL_PITCH");
  CHECK(r.paper[3].mode == 4);
  CHECK(r.paper[3].hz == 8.023328E+01);
}

TEST_CASE("a damaged f06 gives an error naming the file and line") {
  std::string text = read_text_file(kFixture);
  const auto at = text.find("        3         3");
  text.replace(text.find('\n', at) - 20, 20, "");  // drop the last field of mode 3's row
  CHECK_THROWS_WITH(parse_f06(text, "run7/column.f06"),
                    Catch::Contains("run7/column.f06' line 9") && Catch::Contains("6 fields, expected 7"));
  CHECK_THROWS_WITH(parse_f06("1  FATAL MESSAGE 4276\n", "bad.f06"), Catch::Contains("no 'R E A L"));
  CHECK_THROWS_WITH(read_text_file("/nonexistent/x.f06"), Catch::Contains("'/nonexistent/x.f06' is missing"));
}
