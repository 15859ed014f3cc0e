// SPDX-License-Identifier: MIT
// The calibration pipeline behind smi::improve::calibrate: the gradient it chooses,
// the tolerance and prior it reports, and "no overlap" instead of a false "converged".
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/improve/calibration.hpp"
#include "platform/core/rng.hpp"

using namespace smi::improve;

namespace {

/// y1 = a + b², y2 = 3a − b; a normal, b lognormal; data from a ~ N(5, 0.3), b ~ N(2, 0.2) times `scale`.
CalibrationProblem problem(double scale, MetricKind metric = MetricKind::pr) {
  CalibrationProblem p;
  p.params = {{"a.mean", 3, 7, 4.6}, {"a.std", 0.05, 1, 0.4}, {"b.mean", 1, 3, 2.2}, {"b.std", 0.05, 1, 0.3}};
  p.inputs = {{"a", InputFamily::normal, 0, 0, 0, 1, {}}, {"b", InputFamily::lognormal, 0, 0, 2, 3, {}}};
  smi::Rng g(11);
  const Eigen::VectorXd a = g.normal_matrix(40, 1).col(0) * 0.3 + Eigen::VectorXd::Constant(40, 5.0);
  const Eigen::VectorXd b = g.normal_matrix(40, 1).col(0) * 0.2 + Eigen::VectorXd::Constant(40, 2.0);
  ResponseSpec r1, r2;
  r1.name = "y1";
  r1.data = scale * (a.array() + b.array().square()).matrix();
  r2.name = "y2";
  r2.data = scale * (3 * a.array() - b.array()).matrix();
  p.responses = {r1, r2};
  p.stat.n = 500;
  p.stat.grid_nodes = 1001;
  p.stat.seed = 5;
  p.stat.metric = metric;
  p.model = [](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), 2);
    Y.col(0) = (X.col(0).array() + X.col(1).array().square()).matrix();
    Y.col(1) = (3 * X.col(0).array() - X.col(1).array()).matrix();
    return Y;
  };
  return p;
}

}  // namespace

TEST_CASE("calibrate: a model without a Jacobian is differentiated itself (k + 1 passes a gradient) and ends on its tolerances") {
  CalibrationOptions o;
  o.identifiability = false;
  const CalibrationOutcome out = calibrate(problem(1.0), o);
  CHECK(out.gradient == "model_differences");
  CHECK(out.converged);
  CHECK(out.status != "no_overlap");
  // The data's own mean and sd of a and b (40 draws): within a few percent on 500 CRN samples.
  CHECK(out.opt.theta[0] == Approx(5.0).margin(0.15));
  CHECK(out.opt.theta[2] == Approx(2.0).margin(0.1));
  // Each gradient is one model call of 1 + 2 blocks (2 calibrated inputs).
  CHECK(out.stat->model_passes() <= 3 * out.stat->model_runs());
  // PR with the data points at hand: measured from them (test_pr_tolerance.cpp checks the value)
  CHECK(out.tolerance_basis.find("bootstrap resamples of the 40 data rows") != std::string::npos);
  CHECK(out.prior_value == 0.0);

  CalibrationOptions objective_differences = o;
  objective_differences.gradient = "differences";
  const CalibrationOutcome od = calibrate(problem(1.0), objective_differences);
  CHECK(od.gradient == "differences");
  // the same optimum where the data can tell
  CHECK(std::abs(od.opt.value - out.opt.value) < out.tolerance);
}

TEST_CASE("calibrate: tolerance and prior come from the pipeline, not from copies") {
  CalibrationOptions o;
  o.identifiability = false;
  o.optimizer.maxeval = 30;
  CalibrationProblem p = problem(1.0, MetricKind::loglik);
  p.priors.push_back({"a.mean", 0, {}, 5.5, 0.5});
  p.priors.push_back({"ab", -1, [](const Eigen::VectorXd& t) { return t[0] * t[2]; }, 10.0, 2.0});
  o.prior_weight = 2.0;
  const CalibrationOutcome out = calibrate(p, o);
  CHECK(out.tolerance == 1.920729);  // ½ χ²₁(0.95)
  const Eigen::VectorXd& t = out.opt.theta;
  const double expect = 2.0 * (0.5 * std::pow((t[0] - 5.5) / 0.5, 2) + 0.5 * std::pow((t[0] * t[2] - 10.0) / 2.0, 2));
  CHECK(out.prior_value == Approx(expect).epsilon(1e-12));
  CHECK(out.prior_at(t) == Approx(expect).epsilon(1e-12));
  REQUIRE(out.part_names.back() == "prior");
  CHECK(out.opt.parts[out.opt.parts.size() - 1] == Approx(expect).epsilon(1e-12));
}

TEST_CASE("calibrate: predictions 1000x away from the data end as no_overlap, naming the response, ranges and units") {
  CalibrationOptions o;
  o.identifiability = false;
  o.optimizer.maxeval = 40;
  const CalibrationOutcome out = calibrate(problem(1000.0), o);
  INFO("parts " << out.opt.parts.transpose() << " status " << out.status);
  CHECK_FALSE(out.converged);
  CHECK(out.status == "no_overlap");
  REQUIRE(out.no_overlap.size() == 2);
  CHECK(out.no_overlap[0].response == "y1");
  CHECK(out.no_overlap[0].value > 0.9);  // PR on a grid 1000x wider than the prediction: far below 2, still no overlap
  CHECK(out.no_overlap[0].measured_lo > 1000.0);
  CHECK(out.no_overlap[0].predicted_hi < 100.0);
  CHECK(out.message.find("response 'y1'") != std::string::npos);
  CHECK(out.message.find("1/1000 of the data") != std::string::npos);
  CHECK(out.warnings.front() == out.message);

  // loglik: every datum outside the predicted support
  const CalibrationOutcome ll = calibrate(problem(1000.0, MetricKind::loglik), o);
  CHECK(ll.status == "no_overlap");
  CHECK_FALSE(ll.converged);
}

TEST_CASE("units hint: near a power of ten other than 1 only") {
  CHECK(units_hint(1000.0).find("about 1000x") != std::string::npos);
  CHECK(units_hint(0.00105).find("about 1/1000") != std::string::npos);
  CHECK(units_hint(9.3).find("about 10x") != std::string::npos);
  CHECK(units_hint(1.2).empty());
  CHECK(units_hint(30.0).empty());
  CHECK(units_hint(-5.0).empty());
}
