// SPDX-License-Identifier: MIT
// The vectorized exp(-x) of the correlation kernels against std::exp.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "kernels/surrogate/fast_exp.hpp"

TEST_CASE("exp_neg_inplace equals std::exp(-x) to 1e-15 relative over [0, 700]") {
  std::vector<double> x;
  for (int i = 0; i <= 70003; ++i) x.push_back(i * 0.01);  // length not a multiple of 4: scalar tail too
  std::vector<double> y = x;
  smi::surrogate::kriging::exp_neg_inplace(y.data(), static_cast<long>(y.size()));
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(y[i] / std::exp(-x[i]) - 1));
  CHECK(worst < 1e-15);
  std::vector<double> edge = {-1e-17, 0.0, 750.0, 1e300, 1.0};
  smi::surrogate::kriging::exp_neg_inplace(edge.data(), 5);
  CHECK(edge[0] == 1.0);
  CHECK(edge[1] == 1.0);
  CHECK(edge[2] < 1e-300);
  CHECK(edge[3] < 1e-300);
  CHECK(edge[4] == Approx(std::exp(-1.0)).epsilon(1e-15));
}
