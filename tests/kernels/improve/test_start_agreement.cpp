// SPDX-License-Identifier: MIT
// Multistart: whether the starts reached the same optimum where the data can tell
// (start_agreement.hpp), and basin hopping (OptimizerOptions::hops). References are closed forms:
// a valley where the objective is exactly 0 on a line, a double well whose ridge height is 1.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/start_agreement.hpp"
#include "platform/core/errors.hpp"

using namespace smi::improve;

namespace {

Evaluation value(double v) {
  Evaluation e;
  e.value = v;
  return e;
}

/// (x + 2y - 1)^2: zero on a whole line, so the starts stop at different points of it.
Evaluation valley(const Eigen::VectorXd& t) { return value(std::pow(t[0] + 2 * t[1] - 1, 2)); }

/// (m^2 - 1)^2 + tilt (m - 1)^2: minima near m = -1 and at m = 1; the ridge at m = 0.
Objective double_well(double tilt) {
  return [tilt](const Eigen::VectorXd& t) { return value(std::pow(t[0] * t[0] - 1, 2) + tilt * std::pow(t[0] - 1, 2)); };
}

OptimizerOptions tight(int starts) {
  OptimizerOptions o;
  o.multistart = starts;
  o.seed = 3;
  o.xtol_rel = 1e-10;
  o.ftol_abs = 1e-14;
  return o;
}

}  // namespace

TEST_CASE("a valley: starts at different points of it agree where the data can tell") {
  const std::vector<Parameter> p{{"x", -2, 2, 1.5}, {"y", -2, 2, -1.5}};
  const OptimizationResult r = minimize(p, valley, tight(5));
  REQUIRE_FALSE(r.starts_agree);  // distinct points: the strict clustering sees several optima
  const StartAgreement a = start_agreement(p, valley, r, 1e-6);
  CHECK(a.agree);
  CHECK(a.same == 5);
  // between two points of the line the objective is exactly 0: no barrier
  CHECK(a.largest_barrier < 1e-12);
  CHECK(a.evaluations > 0);
}

TEST_CASE("two basins that fit as well, split by a ridge of height 1: not the same optimum") {
  const std::vector<Parameter> p{{"m", -2, 2, -1.5}};
  const Objective f = double_well(0.0);
  const OptimizationResult r = minimize(p, f, tight(6));
  const StartAgreement a = start_agreement(p, f, r, 0.1);
  REQUIRE(a.rows.size() == 6);
  int other = 0;
  for (std::size_t s = 0; s < a.rows.size(); ++s) {
    const bool same_side = r.starts[s].theta[0] * r.theta[0] > 0;
    CHECK(a.rows[s].within);  // both minima are 0
    CHECK(a.rows[s].same == same_side);
    if (!same_side) {
      ++other;
      CHECK(a.rows[s].barrier == Approx(1.0).margin(1e-6));  // the midpoint of -1 and 1 is the ridge, f(0) = 1
    }
  }
  REQUIRE(other > 0);  // the seed's starts fall on both sides
  CHECK_FALSE(a.agree);
}

TEST_CASE("a start whose optimum fits worse than the tolerance needs no path") {
  const std::vector<Parameter> p{{"m", -2, 2, -1.5}};
  const Objective f = double_well(0.1);  // the m = -1 basin sits about 0.4 higher
  OptimizerOptions o = tight(1);
  const OptimizationResult r = minimize(p, f, o);  // the given start only: the upper basin
  REQUIRE(r.theta[0] < 0);
  OptimizationResult two = r;
  two.starts.push_back(r.starts[0]);
  two.starts[1].theta = Eigen::VectorXd::Constant(1, 1.0);
  two.starts[1].value = 0.0;
  two.theta = two.starts[1].theta;
  two.value = 0.0;
  two.best = 1;
  const StartAgreement a = start_agreement(p, f, two, 0.01);
  CHECK_FALSE(a.rows[0].within);
  CHECK(a.rows[0].gap == Approx(r.value).margin(1e-12));
  CHECK(a.rows[1].same);
  CHECK(a.evaluations == 0);
  CHECK_FALSE(a.agree);
}

TEST_CASE("a curved valley: the straight path climbs out of it, the predictions say the same") {
  // (x^2 + 4 y^2 - 1)^2 is 0 on an ellipse; the data would see only x^2 + 4 y^2 (the prediction).
  // Between (1, 0) and (0, 0.5) the straight path's midpoint (0.5, 0.25) has x^2 + 4y^2 = 0.5: f = 0.25.
  const std::vector<Parameter> p{{"x", -2, 2, 1}, {"y", -2, 2, 0}};
  const Objective f = [](const Eigen::VectorXd& t) { return value(std::pow(t[0] * t[0] + 4 * t[1] * t[1] - 1, 2)); };
  OptimizationResult r;
  r.theta = Eigen::Vector2d(1.0, 0.0);
  r.value = 0.0;
  StartResult a, b;
  a.theta = r.theta;
  b.theta = Eigen::Vector2d(0.0, 0.5);
  r.starts = {a, b};
  const StartAgreement by_path = start_agreement(p, f, r, 0.01);
  CHECK_FALSE(by_path.rows[1].same);
  CHECK(by_path.rows[1].barrier == Approx(0.25).margin(1e-12));  // the first point walked is the midpoint
  CHECK(by_path.evaluations == 1);
  PredictionCheck pc;
  pc.summaries = [](const Eigen::VectorXd& t) { return Eigen::VectorXd::Constant(1, t[0] * t[0] + 4 * t[1] * t[1]); };
  pc.resolution = Eigen::VectorXd::Constant(1, 0.1);
  const StartAgreement by_prediction = start_agreement(p, f, r, 0.01, pc);
  CHECK(by_prediction.agree);
  CHECK(by_prediction.rows[1].same_prediction);
  CHECK(by_prediction.rows[1].prediction_distance == Approx(0.0).margin(1e-12));
  CHECK(by_prediction.evaluations == 0);  // no path needed
  CHECK(by_prediction.predictions == 2);
  // a prediction 3 resolutions away is told apart: then the path decides (and finds the ridge)
  pc.summaries = [](const Eigen::VectorXd& t) { return Eigen::VectorXd::Constant(1, t[0] * t[0] + 4 * t[1] * t[1] + 0.3 * t[1] / 0.5); };
  const StartAgreement apart = start_agreement(p, f, r, 0.01, pc);
  CHECK(apart.rows[1].prediction_distance == Approx(3.0).epsilon(1e-12));
  CHECK_FALSE(apart.rows[1].same);
  CHECK_FALSE(apart.agree);
}

TEST_CASE("start agreement rejects a negative tolerance and no path points") {
  const std::vector<Parameter> p{{"m", -2, 2, -1.5}};
  const OptimizationResult r = minimize(p, double_well(0.0), tight(2));
  CHECK_THROWS_AS(start_agreement(p, double_well(0.0), r, -1.0), smi::InvalidArgument);
  CHECK_THROWS_AS(start_agreement(p, double_well(0.0), r, 0.1, {}, 0), smi::InvalidArgument);
}

TEST_CASE("basin hopping: every start of a tilted double well reaches the lower basin") {
  const std::vector<Parameter> p{{"m", -2, 2, -1.5}};
  const Objective f = double_well(0.1);
  const OptimizationResult plain = minimize(p, f, tight(6));
  REQUIRE_FALSE(plain.starts_agree);  // without hops some starts stay in the upper basin
  OptimizerOptions o = tight(6);
  o.hops = 20;  // a hop of up to the whole range lands right of the ridge with probability >= 0.38
  o.hop_step = 1.0;
  const OptimizationResult hopped = minimize(p, f, o);
  CHECK(hopped.starts_agree);
  for (std::size_t s = 0; s < hopped.starts.size(); ++s) {
    CHECK(hopped.starts[s].theta[0] == Approx(1.0).margin(1e-5));
    CHECK(hopped.starts[s].value <= plain.starts[s].value + 1e-12);  // monotone: a hop never makes a start worse
    CHECK(hopped.starts[s].hops == 20);
    CHECK(hopped.starts[s].converged);
  }
  CHECK(hopped.evaluations > plain.evaluations);
}

TEST_CASE("basin hopping on a 2-D Rastrigin function finds the global minimum from every start") {
  // 10 + sum (x^2 - cos(2 pi x)) per coordinate... here in 2 D: minima on the integer grid,
  // the global one 0 at the origin; local methods stop in the first cell they start in.
  const Objective rastrigin = [](const Eigen::VectorXd& t) {
    double v = 20.0;
    for (Eigen::Index i = 0; i < 2; ++i) v += t[i] * t[i] - 10 * std::cos(2 * M_PI * t[i]);
    return value(v);
  };
  const std::vector<Parameter> p{{"x", -3, 3, 2.6}, {"y", -3, 3, -2.2}};
  OptimizerOptions o = tight(4);
  const OptimizationResult plain = minimize(p, rastrigin, o);
  int plain_global = 0;
  for (const StartResult& s : plain.starts) plain_global += s.value < 1e-6;
  o.hops = 60;
  o.hop_step = 0.2;  // a jump of up to 1.2 in each coordinate: a neighbouring cell
  const OptimizationResult hopped = minimize(p, rastrigin, o);
  int global = 0;
  for (const StartResult& s : hopped.starts) global += s.value < 1e-6;
  CHECK(plain_global < 4);
  CHECK(global == 4);
  CHECK(hopped.starts_agree);
}

TEST_CASE("hops and hop_step are checked") {
  const std::vector<Parameter> p{{"m", -2, 2, -1.5}};
  OptimizerOptions o;
  o.hops = -1;
  CHECK_THROWS_AS(minimize(p, double_well(0.0), o), smi::InvalidArgument);
  o.hops = 1;
  o.hop_step = 0.0;
  CHECK_THROWS_AS(minimize(p, double_well(0.0), o), smi::InvalidArgument);
  o.hop_step = 1.5;
  CHECK_THROWS_AS(minimize(p, double_well(0.0), o), smi::InvalidArgument);
}
