// SPDX-License-Identifier: MIT
// Designs: Sobol' points against SciPy (tests/reference/sobol_points.py), Latin property and
// space filling of the optimized LHS, full factorial layout.
#include <catch2/catch.hpp>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "kernels/surrogate/doe.hpp"

using namespace smi::surrogate::doe;

TEST_CASE("Sobol' points equal SciPy's unscrambled sequence in every supported dimension") {
  REQUIRE(sobol_max_dim() == 37);
  const Eigen::MatrixXd X = sobol(511, 37);
  std::ifstream f(SMI_TEST_REFERENCE_DIR "/sobol_points.csv");
  REQUIRE(f.good());
  std::string line;
  int i = 0, mismatches = 0;
  while (std::getline(f, line)) {
    std::stringstream ss(line);
    std::string c;
    for (int j = 0; std::getline(ss, c, ','); ++j)
      if (X(i, j) * 512 != std::stod(c)) ++mismatches;
    ++i;
  }
  CHECK(i == 511);
  CHECK(mismatches == 0);
  CHECK(X.minCoeff() > 0);  // point 0 skipped: quantiles stay finite
  CHECK_THROWS_WITH(sobol(4, 38), Catch::Contains("1..37"));
}

TEST_CASE("LHS: one point per stratum in every column, same seed same design") {
  for (const char* crit : {"none", "maximin", "phip"}) {
    LhsOptions o;
    o.criterion = crit;
    const Eigen::MatrixXd X = lhs(30, 4, 42, o);
    for (int k = 0; k < 4; ++k) {
      std::vector<int> strata;
      for (int i = 0; i < 30; ++i) strata.push_back(static_cast<int>(X(i, k) * 30));
      std::sort(strata.begin(), strata.end());
      for (int i = 0; i < 30; ++i) CHECK(strata[i] == i);
    }
    CHECK(lhs(30, 4, 42, o) == X);
  }
}

TEST_CASE("ESE optimisation improves phi_p and the smallest distance over random LHS") {
  // Average over seeds: the optimised design must beat the random one on every seed.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    LhsOptions none;
    none.criterion = "none";
    const Eigen::MatrixXd R = lhs(40, 3, seed, none), O = lhs(40, 3, seed);
    CHECK(phi_p(O, 50) < phi_p(R, 50));
    CHECK(min_distance(O) > min_distance(R));
  }
}

TEST_CASE("full factorial: first column slowest") {
  const Eigen::MatrixXd X = full_factorial({Eigen::Vector2d(0, 1), Eigen::Vector3d(5, 6, 7)});
  REQUIRE(X.rows() == 6);
  CHECK(X(0, 0) == 0);
  CHECK(X(2, 1) == 7);
  CHECK(X(3, 0) == 1);
  CHECK(X(3, 1) == 5);
}
