// SPDX-License-Identifier: MIT
// Standard normal functions against SciPy (tests/reference/normal_quantile.py), and the
// generator's distributional properties and reproducibility.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <fstream>
#include <sstream>
#include <string>

#include "platform/core/descriptive.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/rng.hpp"

TEST_CASE("normal quantile and cdf agree with scipy.special") {
  std::ifstream in(std::string(SMI_TEST_REFERENCE_DIR) + "/normal_quantile.csv");
  REQUIRE(in.good());
  std::string line;
  std::getline(in, line);  // header
  int rows = 0;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string kind, arg, value;
    std::getline(ss, kind, ',');
    std::getline(ss, arg, ',');
    std::getline(ss, value, ',');
    const double a = std::stod(arg), v = std::stod(value);
    const double got = kind == "quantile" ? smi::normal_quantile(a) : smi::normal_cdf(a);
    INFO(kind << "(" << arg << ")");
    CHECK(got == Approx(v).epsilon(1e-13).margin(1e-300));
    ++rows;
  }
  CHECK(rows >= 25);
}

TEST_CASE("normal quantile edge cases") {
  CHECK(std::isinf(smi::normal_quantile(0.0)));
  CHECK(std::isinf(smi::normal_quantile(1.0)));
  CHECK(std::isnan(smi::normal_quantile(-0.1)));
  CHECK(smi::normal_quantile(0.5) == 0.0);
  CHECK(smi::normal_pdf(0.0) == Approx(0.3989422804014327).epsilon(1e-15));
}

TEST_CASE("the same seed gives the same numbers; streams differ") {
  smi::Rng a(42), b(42), c(42, 1);
  for (int i = 0; i < 100; ++i) CHECK(a.next_u64() == b.next_u64());
  smi::Rng a2(42);
  CHECK(a2.next_u64() != c.next_u64());
}

TEST_CASE("normal sample has the moments of N(0,1)") {
  smi::Rng g(7);
  const Eigen::VectorXd z = g.normal(200000);
  // se of the mean 1/sqrt(n) = 0.0022; of the sd about 0.0016
  CHECK(std::abs(smi::mean(z)) < 0.01);
  CHECK(std::abs(smi::stddev(z) - 1.0) < 0.008);
  // fraction below 1.96 ~ 0.975 (se 0.00035)
  CHECK(std::abs((z.array() < 1.959963985).cast<double>().mean() - 0.975) < 0.002);
}

TEST_CASE("integers are unbiased over a small range") {
  smi::Rng g(3);
  int counts[6] = {0};
  for (int i = 0; i < 60000; ++i) counts[g.integer(1, 6) - 1]++;
  for (int c : counts) CHECK(std::abs(c - 10000) < 500);  // 5 sigma = 456
}

TEST_CASE("type-7 quantile and sd of the spec data (algorithms.md §8.1)") {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  CHECK(smi::mean(x) == Approx(30.251111111).epsilon(1e-10));
  CHECK(smi::stddev(x) == Approx(0.3636084585).epsilon(1e-9));
  CHECK(smi::quantile(x, 0.75) - smi::quantile(x, 0.25) == Approx(0.43).epsilon(1e-12));
  CHECK(smi::mad(x) == Approx(0.25).epsilon(1e-12));
  CHECK_THROWS_WITH(smi::stddev(x.head(1)), Catch::Contains("at least 2"));
  Eigen::VectorXd bad = x;
  bad[3] = std::nan("");
  CHECK_THROWS_WITH(smi::require_finite(bad, "data"), Catch::Contains("data[4] is NaN"));
}

TEST_CASE("integers over the full 64-bit range and ranges wider than 2^63 stay in range") {
  smi::Rng g(7);
  const std::int64_t lo = std::numeric_limits<std::int64_t>::min(), hi = std::numeric_limits<std::int64_t>::max();
  int negative = 0;
  for (int i = 0; i < 1000; ++i) negative += g.integer(lo, hi) < 0;
  CHECK(negative > 400);  // half of the full range is negative: 500 expected, sd 16
  CHECK(negative < 600);
  for (int i = 0; i < 1000; ++i) {
    const std::int64_t v = g.integer(lo, hi / 2);  // span 3 * 2^62: wider than int64
    CHECK(v >= lo);
    CHECK(v <= hi / 2);
  }
  CHECK(g.integer(lo, lo) == lo);
  CHECK(g.integer(hi, hi) == hi);
}
