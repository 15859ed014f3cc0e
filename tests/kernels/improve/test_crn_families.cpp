// SPDX-License-Identifier: MIT
// All nine smi.dist families as calibration inputs: the (mean, std) mapping of
// each family is checked against the family's own closed-form mean and std, the CRN mapping
// against the family's quantile, and the errors name the parameterisation.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/improve/crn_mapping.hpp"
#include "kernels/stats/families.hpp"
#include "platform/core/normal.hpp"

using namespace smi::improve;

TEST_CASE("each family's calibrated mean and std are its mean and std") {
  InputShape shape;
  for (const auto fam : {InputFamily::normal, InputFamily::lognormal, InputFamily::uniform, InputFamily::gumbel,
                         InputFamily::gamma, InputFamily::weibull, InputFamily::triangular}) {
    for (const double cv : {0.05, 0.3, 1.0, 2.5}) {
      if (fam == InputFamily::uniform && cv > 0.5) continue;
      const double mean = 4.0, std = cv * mean;
      const auto d = input_distribution(fam, mean, std, shape, "x");
      INFO(family_name(fam) << " cv " << cv << ": " << d->describe());
      CHECK(d->family() == family_name(fam));
      CHECK(d->mean() == Approx(mean).epsilon(1e-10));
      CHECK(d->stddev() == Approx(std).epsilon(1e-10));
    }
  }
  // Exponential: a Weibull and a gamma with std = mean have shape 1.
  CHECK(input_distribution(InputFamily::weibull, 2.0, 2.0, shape, "x")->field("shape").value() == Approx(1.0).epsilon(1e-12));
  CHECK(input_distribution(InputFamily::gamma, 2.0, 2.0, shape, "x")->field("shape").value() == Approx(1.0).epsilon(1e-15));
  // Fixed shape fields: loc shifts weibull/gamma; beta on [lower, upper]; triangular's mode.
  shape.loc = 1.0;
  CHECK(input_distribution(InputFamily::gamma, 3.0, 0.5, shape, "x")->mean() == Approx(3.0).epsilon(1e-12));
  CHECK(input_distribution(InputFamily::weibull, 3.0, 0.5, shape, "x")->support().first == 1.0);
  shape.lower = 2.0, shape.upper = 6.0;
  const auto b = input_distribution(InputFamily::beta, 3.0, 0.5, shape, "x");
  CHECK(b->mean() == Approx(3.0).epsilon(1e-12));
  CHECK(b->stddev() == Approx(0.5).epsilon(1e-12));
  CHECK(b->support() == std::pair<double, double>(2.0, 6.0));
  shape.mode_at = 0.0;  // right-triangular: mode at the lower end
  const auto t = input_distribution(InputFamily::triangular, 3.0, 0.5, shape, "x");
  CHECK(t->field("mode").value() == Approx(t->field("lower").value()).epsilon(1e-15));
  CHECK(t->stddev() == Approx(0.5).epsilon(1e-12));
  // truncnormal: the parent's mean and std, truncated to the fixed [lower, upper].
  const auto tn = input_distribution(InputFamily::truncnormal, 3.0, 0.5, shape, "x");
  CHECK(tn->field("mean").value() == 3.0);
  CHECK(tn->field("std").value() == 0.5);
  CHECK(tn->support() == std::pair<double, double>(2.0, 6.0));
}

TEST_CASE("CRN mapping of the new families goes through the quantile, both tails precise") {
  Eigen::VectorXd z(7);
  z << -8.0, -2.0, -0.3, 0.0, 0.4, 2.0, 8.0;
  InputShape shape;
  shape.lower = 0.0, shape.upper = 10.0;
  for (const auto fam : {InputFamily::truncnormal, InputFamily::weibull, InputFamily::gumbel, InputFamily::gamma, InputFamily::beta,
                         InputFamily::triangular}) {
    const auto d = input_distribution(fam, 3.0, 1.2, shape, "x");
    const Eigen::VectorXd x = map_standard_normal(fam, 3.0, 1.2, z, "x", shape);
    INFO(d->describe());
    for (Eigen::Index i = 0; i < z.size(); ++i) {
      CHECK(std::isfinite(x[i]));
      // The upper half through isf (Φ(−z), not 1 − Φ(z)): z = 8 keeps sf(x) = 6.2e-16.
      if (z[i] > 0) CHECK(x[i] == d->isf(smi::normal_cdf(-z[i])));
      else CHECK(x[i] == d->quantile(smi::normal_cdf(z[i])));
      // To 1e-9 plus what the solver's stopping tolerance on x (4e-16 relative) does to the tail
      // mass (x at z = ±8 can sit 1e-7 from a finite bound, where the mass is ill-conditioned in x).
      const double want = smi::normal_cdf(-std::abs(z[i]));
      const double cond = std::abs(x[i]) * d->pdf(x[i]) / want;
      const double got = z[i] > 0 ? d->sf(x[i]) : d->cdf(x[i]);
      CHECK(std::abs(got / want - 1.0) <= 1e-9 + 4e-16 * cond);
      if (i > 0) CHECK(x[i] >= x[i - 1]);
    }
  }
}

TEST_CASE("bad family or impossible moments name the culprit and the parameterisation") {
  CHECK_THROWS_WITH(parse_family("weibul", "inputs.k.dist"),
                    Catch::Contains("inputs.k.dist: unknown distribution \"weibull\"") || Catch::Contains("unknown distribution \"weibul\""));
  CHECK_THROWS_WITH(parse_family("weibul", "inputs.k.dist"), Catch::Contains("\"weibull\" (fixed loc = 0)") &&
                                                                 Catch::Contains("parent normal for \"truncnormal\" (fixed lower, upper)") &&
                                                                 Catch::Contains("mode_at"));
  for (const char* f : {"truncnormal", "weibull", "gumbel", "gamma", "beta", "triangular"}) CHECK(family_name(parse_family(f, "x")) == f);
  InputShape shape;
  shape.lower = 0.0, shape.upper = 1.0;
  CHECK_THROWS_WITH(input_distribution(InputFamily::beta, 0.5, 0.6, shape, "input 'k'"),
                    Catch::Contains("input 'k'") && Catch::Contains("std < sqrt((mean - lower)(upper - mean)) = 0.5"));
  CHECK_THROWS_WITH(input_distribution(InputFamily::gamma, -1.0, 0.5, InputShape{}, "input 'k'"), Catch::Contains("mean > loc"));
  Eigen::VectorXd z = Eigen::VectorXd::Zero(1);
  CHECK_THROWS_WITH(map_standard_normal(InputFamily::weibull, 1.0, 1e6, z, "input 'w'"), Catch::Contains("input 'w'"));
}
