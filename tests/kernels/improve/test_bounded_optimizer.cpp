// SPDX-License-Identifier: MIT
// Bound-constrained calibration optimiser: closed-form minima, bounds, multistart, errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "kernels/improve/bounded_optimizer.hpp"
#include "platform/core/errors.hpp"

using namespace smi::improve;

namespace {
Evaluation quad(const Eigen::VectorXd& t) {
  Evaluation e;
  e.parts.resize(2);
  e.parts << (t[0] - 1.3) * (t[0] - 1.3), 10 * (t[1] - 0.2) * (t[1] - 0.2);
  e.value = e.parts.sum();
  return e;
}
std::vector<Parameter> quad_params() { return {{"a", 0.0, 2.0, 0.1}, {"b", -1.0, 1.0, 0.9}}; }
}  // namespace

TEST_CASE("every method finds the minimum of a quadratic in the box") {
  for (const char* m : {"slsqp", "lbfgs", "cobyla", "bobyqa", "neldermead"}) {
    OptimizerOptions o;
    o.method = parse_method(m);
    o.xtol_rel = 1e-10;
    o.ftol_abs = 1e-14;
    const OptimizationResult r = minimize(quad_params(), quad, o);
    INFO(m << " status " << r.status);
    CHECK(r.theta[0] == Approx(1.3).margin(1e-4));
    CHECK(r.theta[1] == Approx(0.2).margin(1e-4));
    CHECK(r.value < 1e-7);
    CHECK(r.converged);
    CHECK(r.parts.size() == 2);
    CHECK(static_cast<int>(r.history.size()) == r.evaluations);
    CHECK(r.at_bounds.empty());
  }
}

TEST_CASE("L-BFGS with an analytic gradient: a minimum on a bound, no probes; its name is parsed") {
  // (t0 + 1)² + 10 (t1 − 0.2)² on [0, 2] × [−1, 1]: the minimum is (0, 0.2), t0 on its lower bound.
  auto f = [](const Eigen::VectorXd& t) { return Evaluation{(t[0] + 1) * (t[0] + 1) + 10 * (t[1] - 0.2) * (t[1] - 0.2), {}}; };
  OptimizerOptions o;
  o.method = parse_method("l-bfgs");
  CHECK(method_name(o.method) == "lbfgs");
  CHECK(uses_gradient(o.method));
  o.xtol_rel = 1e-10;
  int gradient_calls = 0;
  o.gradient = [&](const Eigen::VectorXd& t, Eigen::VectorXd& g) {
    ++gradient_calls;
    g.resize(2);
    g << 2 * (t[0] + 1), 20 * (t[1] - 0.2);
    return f(t);
  };
  const OptimizationResult r = minimize(quad_params(), f, o);
  CHECK(r.theta[0] == Approx(0.0).margin(1e-8));
  CHECK(r.theta[1] == Approx(0.2).margin(1e-6));
  CHECK(r.converged);
  REQUIRE(r.at_bounds.size() == 1);
  CHECK(r.at_bounds[0] == "a");
  CHECK(gradient_calls == r.evaluations);  // every L-BFGS evaluation is a value and a gradient
  for (const auto& h : r.history) CHECK_FALSE(h.probe);
  CHECK_THROWS_WITH(parse_method("bfgs"), Catch::Contains("lbfgs"));
}

TEST_CASE("SLSQP's gradient probes are recorded and counted") {
  OptimizerOptions o;
  const OptimizationResult r = minimize(quad_params(), quad, o);
  int probes = 0;
  for (const auto& h : r.history) probes += h.probe;
  const int points = static_cast<int>(r.history.size()) - probes;
  CHECK(probes > 0);
  CHECK(probes <= 4 * points);  // at most two probes per parameter and point (one at a bound)
  CHECK(r.evaluations == static_cast<int>(r.history.size()));
}

TEST_CASE("a minimum on a bound is reported; 1-parameter BOBYQA falls back to COBYLA") {
  std::vector<Parameter> p{{"a", 0.0, 2.0, 1.5}};
  auto f = [](const Eigen::VectorXd& t) { return Evaluation{(t[0] + 1) * (t[0] + 1), {}}; };
  OptimizerOptions o;
  o.method = Method::bobyqa;
  const OptimizationResult r = minimize(p, f, o);
  CHECK(r.theta[0] == Approx(0.0).margin(1e-6));
  REQUIRE(r.at_bounds.size() == 1);
  CHECK(r.at_bounds[0] == "a");
  bool fell_back = false;
  for (const auto& w : r.warnings) fell_back = fell_back || w.find("cobyla") != std::string::npos;
  CHECK(fell_back);
}

TEST_CASE("multistart escapes a local minimum") {
  // f = (x² − 1)² + 0.3x: minima at the roots of 4x³ − 4x + 0.3 near ±1; the left one is global.
  auto f = [](const Eigen::VectorXd& t) {
    const double x = t[0];
    return Evaluation{(x * x - 1) * (x * x - 1) + 0.3 * x, {}};
  };
  // The global minimiser by bisection of f' on [-2, -0.5].
  double lo = -2, hi = -0.5;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((4 * mid * mid * mid - 4 * mid + 0.3) < 0 ? lo : hi) = mid;
  }
  std::vector<Parameter> p{{"x", -2.0, 2.0, 1.5}};
  OptimizerOptions o;
  o.method = Method::slsqp;
  const OptimizationResult one = minimize(p, f, o);
  CHECK(one.theta[0] > 0);
  o.multistart = 8;
  o.seed = 3;
  const OptimizationResult many = minimize(p, f, o);
  CHECK(many.theta[0] == Approx(lo).margin(1e-4));
  CHECK(many.starts.size() == 8);
  CHECK(many.value < one.value);
  // Same seed, same starts.
  const OptimizationResult again = minimize(p, f, o);
  CHECK(again.evaluations == many.evaluations);
  CHECK(again.theta[0] == many.theta[0]);
  // Starts side by side: the same starts, history (in start order), optima and warnings.
  o.start_threads = 2;
  const OptimizationResult side = minimize(p, f, o);
  REQUIRE(side.history.size() == many.history.size());
  for (std::size_t i = 0; i < side.history.size(); ++i) {
    CHECK(side.history[i].start == many.history[i].start);
    CHECK(side.history[i].theta[0] == many.history[i].theta[0]);
    CHECK(side.history[i].value == many.history[i].value);
  }
  CHECK(side.theta[0] == many.theta[0]);
  CHECK(side.optima == many.optima);
  CHECK(side.warnings == many.warnings);
  for (std::size_t s = 0; s < side.starts.size(); ++s) CHECK(side.starts[s].given[0] == many.starts[s].given[0]);
}

TEST_CASE("the objective's own exception comes out of minimize with its message") {
  int calls = 0;
  auto f = [&](const Eigen::VectorXd& t) {
    if (++calls == 5) throw std::domain_error("solver run 17 failed: deck line 3");
    return quad(t);
  };
  for (const char* m : {"slsqp", "cobyla"}) {
    calls = 0;
    OptimizerOptions o;
    o.method = parse_method(m);
    CHECK_THROWS_AS(minimize(quad_params(), f, o), std::domain_error);
    calls = 0;
    CHECK_THROWS_WITH(minimize(quad_params(), f, o), Catch::Contains("solver run 17 failed: deck line 3"));
  }
}

TEST_CASE("a NaN objective and bad parameters are clear errors") {
  auto nan = [](const Eigen::VectorXd&) { return Evaluation{std::nan(""), {}}; };
  CHECK_THROWS_WITH(minimize(quad_params(), nan, {}), Catch::Contains("a = 0.1") && Catch::Contains("finite"));
  CHECK_THROWS_WITH(minimize({{"s", 1.0, 0.5, 0.7}}, quad, {}), Catch::Contains("'s'") && Catch::Contains("lower < upper"));
  CHECK_THROWS_WITH(minimize({{"s", 0.0, 1.0, 2.0}}, quad, {}), Catch::Contains("outside its bounds"));
  CHECK_THROWS_WITH(parse_method("newton"), Catch::Contains("\"cobyla\""));
}

TEST_CASE("a small budget stops with a warning and the best point") {
  OptimizerOptions o;
  o.maxeval = 12;
  const OptimizationResult r = minimize(quad_params(), quad, o);
  CHECK(r.evaluations <= 12);
  CHECK(!r.converged);
  CHECK(r.status == "maxeval_reached");
  CHECK(r.value <= quad(Eigen::Vector2d(0.1, 0.9)).value);
}

TEST_CASE("central differences match the analytic gradient") {
  Eigen::VectorXd t(2), h(2);
  t << 0.4, -0.3;
  h << 1e-4, 1e-4;
  const Eigen::VectorXd g = central_gradient(quad, t, h);
  CHECK(g[0] == Approx(2 * (0.4 - 1.3)).epsilon(1e-8));
  CHECK(g[1] == Approx(20 * (-0.3 - 0.2)).epsilon(1e-8));
}

namespace {
/// Rosenbrock's valley in 4 dimensions: SLSQP's line searches reject many full steps on it.
double rosen(const Eigen::VectorXd& t) {
  double f = 0.0;
  for (Eigen::Index i = 0; i + 1 < t.size(); ++i) f += 100 * std::pow(t[i + 1] - t[i] * t[i], 2) + std::pow(1 - t[i], 2);
  return f;
}
Eigen::VectorXd rosen_gradient(const Eigen::VectorXd& t) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(t.size());
  for (Eigen::Index i = 0; i + 1 < t.size(); ++i) {
    const double d = t[i + 1] - t[i] * t[i];
    g[i] += -400 * t[i] * d - 2 * (1 - t[i]);
    g[i + 1] += 200 * d;
  }
  return g;
}
std::vector<Parameter> rosen_params() { return {{"a", -2, 2, -1.2}, {"b", -2, 2, 1}, {"c", -2, 2, -1.2}, {"d", -2, 2, 1}}; }

/// The points SLSQP asked for (finite-difference probes left out) and their values.
std::vector<std::pair<Eigen::VectorXd, double>> asked(const OptimizationResult& r) {
  std::vector<std::pair<Eigen::VectorXd, double>> out;
  for (const HistoryEntry& h : r.history)
    if (!h.probe) out.emplace_back(h.theta, h.value);
  return out;
}
}  // namespace

TEST_CASE("defer_gradient: SLSQP's iterates are the same bit for bit, without the gradients of rejected line-search trials") {
  // NLopt's SLSQP asks for the gradient at the first trial of every line search and drops it when
  // the trial fails the sufficient-decrease test; deferred, those gradients are not computed.
  OptimizerOptions o;
  o.xtol_rel = 1e-10;
  o.ftol_abs = 1e-14;
  o.maxeval = 2000;
  SECTION("analytic gradient: fewer gradient calls, one per accepted point") {
    int calls = 0;
    o.gradient = [&calls](const Eigen::VectorXd& t, Eigen::VectorXd& g) {
      ++calls;
      g = rosen_gradient(t);
      return Evaluation{rosen(t), {}};
    };
    const Objective f = [](const Eigen::VectorXd& t) { return Evaluation{rosen(t), {}}; };
    o.defer_gradient = false;
    const OptimizationResult plain = minimize(rosen_params(), f, o);
    const int plain_calls = calls;
    calls = 0;
    o.defer_gradient = true;
    const OptimizationResult deferred = minimize(rosen_params(), f, o);
    INFO("gradients " << plain_calls << " -> " << calls << ", deferred " << deferred.starts[0].deferred_gradients);
    CHECK(plain.converged);
    CHECK(plain.theta.isApprox(Eigen::VectorXd::Ones(4), 1e-4));
    CHECK(deferred.starts[0].deferred_gradients >= 5);
    CHECK(plain.starts[0].deferred_gradients == 0);
    CHECK(calls == plain_calls - deferred.starts[0].deferred_gradients);
    CHECK(deferred.evaluations == plain.evaluations);
    CHECK(asked(deferred) == asked(plain));
    CHECK(deferred.theta == plain.theta);
    CHECK(deferred.status == plain.status);
    CHECK(deferred.warnings == plain.warnings);
  }
  SECTION("central differences of the objective: 2k probes saved per rejected trial") {
    const Objective f = [](const Eigen::VectorXd& t) { return Evaluation{rosen(t), {}}; };
    o.fd_step = 1e-6;
    o.defer_gradient = false;
    const OptimizationResult plain = minimize(rosen_params(), f, o);
    o.defer_gradient = true;
    const OptimizationResult deferred = minimize(rosen_params(), f, o);
    const int saved = deferred.starts[0].deferred_gradients;
    INFO("evaluations " << plain.evaluations << " -> " << deferred.evaluations << ", deferred " << saved);
    CHECK(saved >= 5);
    CHECK(asked(deferred) == asked(plain));
    CHECK(deferred.theta == plain.theta);
    // each skipped gradient had between k = 4 probes (one-sided at bounds) and 2k = 8 (central)
    CHECK(deferred.evaluations <= plain.evaluations - 4 * saved);
    CHECK(deferred.evaluations >= plain.evaluations - 8 * saved);
  }
}
