// SPDX-License-Identifier: MIT
// CRN parameter mapping (spec §7) against the parameterisation values of spec §8.5.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "kernels/improve/crn_mapping.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"

using namespace smi::improve;

TEST_CASE("lognormal parameterisation by mean and std (spec 8.5)") {
  const LognormalParams a = lognormal_params(5.5, 0.18);
  CHECK(a.mu_ln == Approx(1.7042128416).epsilon(1e-10));
  CHECK(a.sigma_ln == Approx(0.0327185145).epsilon(1e-9));
  Eigen::VectorXd z(1);
  z << 1.0;
  CHECK(map_standard_normal(InputFamily::lognormal, 5.5, 0.18, z, "x")[0] == Approx(5.6798871019).epsilon(1e-10));
  const LognormalParams b = lognormal_params(3.2, 0.14);
  CHECK(b.mu_ln == Approx(1.1621946933).epsilon(1e-10));
  CHECK(b.sigma_ln == Approx(0.0437290866).epsilon(1e-9));
}

TEST_CASE("uniform parameterisation by mean and std (spec 8.5)") {
  const UniformBounds u = uniform_bounds(1.0, 0.16);
  CHECK(u.lower == Approx(0.7228718708).epsilon(1e-10));
  CHECK(u.upper == Approx(1.2771281292).epsilon(1e-10));
  Eigen::VectorXd z(1);
  z << 1.0;
  CHECK(map_standard_normal(InputFamily::uniform, 1.0, 0.16, z, "x")[0] == Approx(1.1891924618).epsilon(1e-10));
}

TEST_CASE("normal mapping and sample moments of each family") {
  const Eigen::MatrixXd Z = crn_matrix(20000, 1, 7, CrnKind::quantiles);
  for (auto fam : {InputFamily::normal, InputFamily::lognormal, InputFamily::uniform}) {
    const Eigen::VectorXd x = map_standard_normal(fam, 3.0, 0.4, Z.col(0), "x");
    const double m = x.mean();
    const double s = std::sqrt((x.array() - m).square().sum() / (x.size() - 1));
    CHECK(m == Approx(3.0).epsilon(1e-4));
    CHECK(s == Approx(0.4).epsilon(2e-3));  // quantile points: tails truncated at ±4.05
  }
}

TEST_CASE("lognormal with mean <= 0 and negative std are clear errors") {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(3);
  CHECK_THROWS_WITH(map_standard_normal(InputFamily::lognormal, 0.0, 0.1, z, "input 'k'"),
                    Catch::Contains("input 'k'") && Catch::Contains("mean > 0"));
  CHECK_THROWS_AS(lognormal_params(-1.0, 0.1), smi::InvalidArgument);
  CHECK_THROWS_WITH(map_standard_normal(InputFamily::normal, 1.0, -0.1, z, "input 'k'"), Catch::Contains("std >= 0"));
  CHECK_THROWS_WITH(parse_family("gama", "input 'k'"), Catch::Contains("\"lognormal\""));
}

TEST_CASE("CRN matrices: quantile points, permuted columns, same seed same matrix") {
  const Eigen::MatrixXd Q = crn_matrix(2000, 3, 11, CrnKind::quantiles);
  CHECK(Q(0, 0) == Approx(smi::normal_quantile(0.5 / 2000)).epsilon(1e-14));
  CHECK(Q(1999, 0) == Approx(smi::normal_quantile(1999.5 / 2000)).epsilon(1e-14));
  for (int j = 1; j < 3; ++j) {
    Eigen::VectorXd c = Q.col(j);
    std::sort(c.data(), c.data() + c.size());
    CHECK((c - Q.col(0)).cwiseAbs().maxCoeff() == 0.0);  // a permutation of column 0
    CHECK(Q.col(j) != Q.col(0));
  }
  CHECK(crn_matrix(100, 2, 5) == crn_matrix(100, 2, 5));
  CHECK(crn_matrix(100, 2, 5) != crn_matrix(100, 2, 6));
}
