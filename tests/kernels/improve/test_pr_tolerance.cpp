// SPDX-License-Identifier: MIT
// The PR tolerance measured from the data (pr_tolerance.hpp) against NumPy
// (tests/reference/pr_tolerance.py -> pr_tolerance.json): the standard deviation of the summed PR
// over paired resamples of 9 rows, the prediction y1 = a, y2 = a + b of normal inputs written in
// closed form there. And through calibrate(): r.tolerance is that measurement where the data
// points are at hand, the unit-free default where they are not (or resamples = 0).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "kernels/improve/calibration.hpp"
#include "kernels/improve/pr_tolerance.hpp"
#include "kernels/stats/kde.hpp"
#include "platform/core/json.hpp"

using namespace smi::improve;

namespace {

smi::json::Value reference() {
  std::ifstream f(std::string(SMI_TEST_REFERENCE_DIR) + "/pr_tolerance.json");
  REQUIRE(f.good());
  std::stringstream s;
  s << f.rdbuf();
  return smi::json::read(s.str(), "pr_tolerance.json");
}

double number(const smi::json::Value& v, const char* key) { return v.find(key)->number(); }

/// The reference's problem: a ~ N(10, 1), b ~ N(5, 0.5) as calibrated parameters at θ, y1 = a,
/// y2 = a + b, its 9 data rows and grids.
CalibrationProblem problem(const smi::json::Value& ref) {
  CalibrationProblem p;
  p.params = {{"a.mean", 8, 12, 10}, {"a.std", 0.2, 2, 1}, {"b.mean", 3, 7, 5}, {"b.std", 0.1, 1, 0.5}};
  p.inputs = {{"a", InputFamily::normal, 0, 0, 0, 1, {}}, {"b", InputFamily::normal, 0, 0, 2, 3, {}}};
  const auto& rows = ref.find("rows")->array();
  const auto& grids = ref.find("grids")->array();
  for (int r = 0; r < 2; ++r) {
    ResponseSpec s;
    s.name = r == 0 ? "y1" : "y2";
    s.data.resize(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) s.data[static_cast<Eigen::Index>(i)] = rows[i].array()[static_cast<std::size_t>(r)].number();
    const auto& g = grids[static_cast<std::size_t>(r)].array();
    s.grid = smi::stats::Grid{g[0].number(), g[1].number(), static_cast<Eigen::Index>(g[2].number())};
    p.responses.push_back(s);
  }
  p.stat.n = static_cast<Eigen::Index>(number(ref, "n"));
  p.stat.seed = 3;
  p.model = [](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), 2);
    Y.col(0) = X.col(0);
    Y.col(1) = X.col(0) + X.col(1);
    return Y;
  };
  return p;
}

StatisticalObjective objective(const CalibrationProblem& p) {
  return StatisticalObjective(p.inputs, p.responses, p.params, p.model, p.stat);
}

Eigen::VectorXd theta() { return (Eigen::VectorXd(4) << 10.0, 1.0, 5.0, 0.5).finished(); }

}  // namespace

TEST_CASE("PR tolerance: the spread of the summed PR over paired resamples of the rows is NumPy's") {
  const auto ref = reference();
  const StatisticalObjective obj = objective(problem(ref));
  REQUIRE(can_measure_pr_tolerance(obj));
  // the summed PR at the data themselves: the closed-form prediction stands in for the kernel's
  // KDE of 5000 CRN outputs to within its sampling noise
  CHECK(obj(theta()).value == Approx(number(ref, "at_data")).margin(0.03));
  const int B = 2000;
  const PrTolerance t = measure_pr_tolerance(obj, theta(), B, 7, 2);
  CHECK(t.resamples + t.failed == B);
  CHECK(t.paired);
  // The standard deviation of B resamples has a relative error of about 1/sqrt(2(B - 1)) = 1.6 %
  // (a little more for a skewed sum): 6 % is four of those; the mean's error is sd/sqrt(B).
  CHECK(t.value == Approx(number(ref, "std")).epsilon(0.06));
  CHECK(t.mean == Approx(number(ref, "mean")).margin(4.0 * number(ref, "std") / std::sqrt(B) + 0.03));
}

TEST_CASE("PR tolerance: named streams make it independent of the threads, and the seed moves it within its error") {
  const auto ref = reference();
  const StatisticalObjective obj = objective(problem(ref));
  const PrTolerance one = measure_pr_tolerance(obj, theta(), 200, 11, 1);
  const PrTolerance two = measure_pr_tolerance(obj, theta(), 200, 11, 2);
  CHECK(one.value == two.value);
  CHECK(one.mean == two.mean);
  const PrTolerance other = measure_pr_tolerance(obj, theta(), 200, 12, 2);
  CHECK(other.value != one.value);
  CHECK(other.value == Approx(one.value).epsilon(0.25));  // 200 resamples: about 5 % each
}

TEST_CASE("PR tolerance: calibrate() reports the measured one where data points are at hand, the default otherwise") {
  const auto ref = reference();
  CalibrationOptions o;
  o.identifiability = false;
  o.optimizer.maxeval = 1;  // the tolerance at the start: θ of the reference
  const CalibrationProblem p = problem(ref);
  const CalibrationOutcome measured = calibrate(p, o);
  REQUIRE(measured.opt.theta.isApprox(theta(), 1e-9));
  const PrTolerance direct = measure_pr_tolerance(*measured.stat, theta(), kPrToleranceResamples, p.stat.seed, 1);
  CHECK(measured.tolerance == Approx(direct.value).epsilon(1e-12));
  CHECK(measured.tolerance_basis.find("1000 bootstrap resamples of the 9 data rows") != std::string::npos);
  CHECK(measured.tolerance == Approx(number(ref, "std")).epsilon(0.15));

  CalibrationOptions fixed = o;
  fixed.tolerance_resamples = 0;
  CHECK(calibrate(p, fixed).tolerance == 0.02);  // 0.01 per response

  // a PDF given without its points: nothing to resample, the default
  CalibrationProblem pdf_only = p;
  for (ResponseSpec& r : pdf_only.responses) {
    r.f_exp = smi::stats::make_kde(r.data, "silverman");
    r.data.resize(0);
  }
  CHECK(calibrate(pdf_only, o).tolerance == 0.02);
  // the PDF with its points: the objective takes the PDF, the tolerance resamples the points
  CalibrationProblem both = p;
  for (ResponseSpec& r : both.responses) r.f_exp = smi::stats::make_kde(r.data, "silverman");
  CHECK(calibrate(both, o).tolerance == Approx(direct.value).epsilon(1e-12));
}
