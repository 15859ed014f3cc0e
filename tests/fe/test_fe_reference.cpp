// SPDX-License-Identifier: MIT
// smi-column-fe against the reference values of docs/spec/steering-column.md §11 (and §6).
#include <catch2/catch.hpp>

#include "fe_test_util.hpp"

using cfe::Airbag;
using fe_test::half_unit;

namespace {

void check_all_ten(Airbag a, const std::array<double, 10>& ref) {
  const cfe::Results r = cfe::run_model(cfe::nominal_inputs(a));
  REQUIRE(r.modes.size() == 10);
  for (int k = 0; k < 10; ++k) {
    INFO("mode " << k + 1 << ": " << r.modes[k].cycles << " Hz vs " << ref[k]);
    CHECK(std::abs(r.modes[k].cycles - ref[k]) <= half_unit(ref[k], 6));
  }
}

void check_paper(const cfe::Inputs& in, const std::array<double, 4>& ref) {
  const auto f = fe_test::paper_hz(in);
  for (int m = 0; m < 4; ++m) {
    INFO("paper mode " << m + 1 << ": " << f[m] << " Hz vs " << ref[m]);
    CHECK(std::abs(f[m] - ref[m]) <= half_unit(ref[m], 4));
  }
}

}  // namespace

TEST_CASE("all 10 nominal modes match spec §11 to 6 significant digits", "[fe][reference]") {
  check_all_ten(Airbag::rigid, {29.6372, 33.5958, 38.2634, 80.2333, 97.3035, 119.652, 143.148, 160.905, 225.682, 256.353});
  check_all_ten(Airbag::spring, {29.6953, 33.3360, 38.4813, 72.6656, 89.1659, 90.7440, 110.996, 125.564, 128.898, 145.043});
}

TEST_CASE("paper modes of the §11 table, r = 1 and r = 2", "[fe][reference]") {
  check_paper(cfe::nominal_inputs(Airbag::rigid), {29.64, 33.60, 38.26, 80.23});
  check_paper(cfe::nominal_inputs(Airbag::spring), {29.70, 33.34, 38.48, 72.67});
  check_paper(cfe::nominal_inputs(Airbag::rigid, 2), {29.60, 33.54, 38.02, 79.75});
  check_paper(cfe::nominal_inputs(Airbag::spring, 2), {29.66, 33.27, 38.25, 72.45});
}

TEST_CASE("at the §8 corner the lateral mode comes first and labels still find paper modes", "[fe][reference]") {
  check_paper(fe_test::corner(Airbag::rigid), {44.12, 41.67, 50.52, 111.0});
  check_paper(fe_test::corner(Airbag::spring), {43.83, 40.95, 50.74, 79.69});
  const cfe::Results r = cfe::run_model(fe_test::corner(Airbag::rigid));
  CHECK(r.modes[0].direction == "LATERAL");
  CHECK(r.paper_mode[1] == 1);  // paper mode 2 is mode 1
  CHECK(r.paper_mode[0] == 2);
}

TEST_CASE("mode 1 converges under mesh refinement (r = 1, 2, 4 within 1 %)", "[fe][reference]") {
  const double f1 = fe_test::paper_hz(cfe::nominal_inputs(Airbag::rigid, 1))[0];
  const double f2 = fe_test::paper_hz(cfe::nominal_inputs(Airbag::rigid, 2))[0];
  const double f4 = fe_test::paper_hz(cfe::nominal_inputs(Airbag::rigid, 4))[0];
  CHECK(std::abs(f4 - 29.59) <= half_unit(29.59, 4));
  CHECK(std::abs(f2 - f1) / f1 < 0.01);
  CHECK(std::abs(f4 - f1) / f1 < 0.01);
  CHECK(f4 < f2);  // consistent-mass Euler-Bernoulli converges from above
  CHECK(f2 < f1);
}

TEST_CASE("airbag refinement A -> B shifts the modes as in spec §6", "[fe][reference]") {
  const auto a = fe_test::paper_hz(cfe::nominal_inputs(Airbag::rigid));
  const auto b = fe_test::paper_hz(cfe::nominal_inputs(Airbag::spring));
  auto pct = [&](int m) { return 100.0 * (b[m] - a[m]) / a[m]; };
  CHECK(pct(3) == Approx(-9.4).margin(0.05));
  CHECK(pct(0) == Approx(0.2).margin(0.05));
  CHECK(pct(1) == Approx(-0.8).margin(0.05));
}
