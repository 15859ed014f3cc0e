// SPDX-License-Identifier: MIT
// CRN calibration by probability residual, against spec §8.2: y = x, x = μ + σz with
// z_i = Φ⁻¹((i − ½)/2000), f_exp = KDE of the §8.1 data (normal-reference h), grid [27, 33.5]
// with 6501 nodes.
#include <catch2/catch.hpp>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/statistical_objective.hpp"

using namespace smi::improve;

namespace {
Eigen::VectorXd spec_data() {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  return x;
}

StatisticalObjective spec_objective(double mu0 = 30.0, double s0 = 0.5) {
  std::vector<Parameter> p{{"x.mean", 29.0, 31.0, mu0}, {"x.std", 0.05, 1.0, s0}};
  InputSpec in{"x", InputFamily::normal, 0.0, 0.0, 0, 1, {}};
  ResponseSpec r;
  r.name = "y";
  r.data = spec_data();
  r.grid = smi::stats::Grid{27.0, 33.5, 6501};
  StatisticalOptions o;
  o.n = 2000;
  o.crn = CrnKind::quantiles;
  return StatisticalObjective({in}, {r}, p, [](const Eigen::MatrixXd& X) { return X; }, o);
}
}  // namespace

TEST_CASE("spec 8.2: PR values on the CRN set-up") {
  const StatisticalObjective f = spec_objective();
  CHECK(f(Eigen::Vector2d(30.0, 0.5)).value == Approx(0.4181069).epsilon(2e-7));
  CHECK(f(Eigen::Vector2d(30.25, 0.36)).value == Approx(0.1820371).epsilon(5e-7));
  CHECK(f.model_runs() == 2);
}

TEST_CASE("spec 8.2: dPR/dmu at (30.1, 0.4) by central differences is step-independent under CRN (steps 1e-4..1e-7)") {
  const StatisticalObjective f = spec_objective();
  Objective obj = [&](const Eigen::VectorXd& t) { return f(t); };
  for (double h : {1e-4, 1e-5, 1e-6, 1e-7}) {
    const Eigen::VectorXd g = central_gradient(obj, Eigen::Vector2d(30.1, 0.4), Eigen::Vector2d(h, h));
    INFO("step " << h);
    CHECK(g[0] == Approx(-1.76617).epsilon(2e-5));
  }
}

TEST_CASE("spec 8.2: SLSQP from (30.0, 0.5) reaches (30.21768, 0.42734), PR 0.0786579") {
  const StatisticalObjective f = spec_objective();
  OptimizerOptions o;  // SLSQP, central differences 1e-4 scaled, xtol_rel 1e-6, ftol_abs 1e-8
  const OptimizationResult r = minimize(f.parameters(), [&](const Eigen::VectorXd& t) { return f(t); }, o);
  INFO("status " << r.status << ", evaluations " << r.evaluations);
  CHECK(r.theta[0] == Approx(30.21768).margin(3e-5));
  CHECK(r.theta[1] == Approx(0.42734).margin(2e-5));
  CHECK(r.value == Approx(0.0786579).margin(2e-7));
  CHECK(r.converged);
  CHECK(r.parts.size() == 1);

  SECTION("Nelder-Mead agrees") {
    OptimizerOptions nm;
    nm.method = Method::neldermead;
    nm.xtol_rel = 1e-9;
    nm.ftol_abs = 1e-12;
    nm.maxeval = 2000;
    const OptimizationResult q = minimize(f.parameters(), [&](const Eigen::VectorXd& t) { return f(t); }, nm);
    CHECK(q.theta[0] == Approx(r.theta[0]).margin(5e-5));
    CHECK(q.theta[1] == Approx(r.theta[1]).margin(5e-5));
    CHECK(q.value == Approx(0.0786579).margin(2e-7));
  }
}

TEST_CASE("negative log-likelihood metric and mass outside the grid") {
  std::vector<Parameter> p{{"x.mean", 29.0, 31.0, 30.0}, {"x.std", 0.05, 1.0, 0.5}};
  InputSpec in{"x", InputFamily::normal, 0.0, 0.0, 0, 1, {}};
  ResponseSpec r;
  r.name = "y";
  r.data = spec_data();
  r.grid = smi::stats::Grid{27.0, 33.5, 6501};
  StatisticalOptions o;
  o.crn = CrnKind::quantiles;
  // Far from the data the prediction leaves the grid: PR must saturate at 2, not drop.
  StatisticalObjective far({in}, {r}, {{"x.mean", 29.0, 40.0, 30.0}, {"x.std", 0.05, 1.0, 0.5}},
                           [](const Eigen::MatrixXd& X) { return X; }, o);
  CHECK(far(Eigen::Vector2d(38.0, 0.3)).value == Approx(2.0).margin(1e-6));
  o.metric = MetricKind::loglik;
  StatisticalObjective ll({in}, {r}, p, [](const Eigen::MatrixXd& X) { return X; }, o);
  // With a KDE of 2000 normal quantile points the density is close to the N(30.25, 0.36²) one:
  // spec 8.2 gives -log L = 3.1562182871 for the analytic PDF.
  CHECK(ll(Eigen::Vector2d(30.25, 0.36)).value == Approx(3.1562182871).epsilon(0.03));
}

TEST_CASE("lognormal mean range reaching 0 is refused before any model run") {
  InputSpec in{"k", InputFamily::lognormal, 0.0, 0.1, 0, -1, {}};
  ResponseSpec r;
  r.name = "y";
  r.data = spec_data();
  int runs = 0;
  CHECK_THROWS_WITH(StatisticalObjective({in}, {r}, {{"k.mean", 0.0, 2.0, 1.0}}, [&](const Eigen::MatrixXd& X) { ++runs; return X; }, {}),
                    Catch::Contains("input 'k'") && Catch::Contains("mean > 0"));
  CHECK(runs == 0);
}
