// SPDX-License-Identifier: MIT
// The calibration objective's analytic gradient against central differences
// of the objective itself, on CRN: quantile functions of normal, lognormal and uniform inputs,
// a model Jacobian, the KDE with its bandwidth (sd-based, IQR-based robust, MAD), PR (with outside mass)
// and loglik.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/input_derivatives.hpp"
#include "kernels/improve/overlap_start.hpp"
#include "kernels/improve/statistical_objective.hpp"
#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde_coarse_grid.hpp"
#include "platform/core/rng.hpp"

using namespace smi::improve;

TEST_CASE("input derivatives: closed forms agree with differences of the mapping") {
  smi::Rng g(3);
  const Eigen::VectorXd z = g.normal_matrix(200, 1).col(0);
  for (InputFamily f : {InputFamily::normal, InputFamily::lognormal, InputFamily::uniform, InputFamily::constant})
    for (auto [m, s] : {std::pair{2.0, 0.3}, std::pair{5.0, 2.0}, std::pair{0.7, 0.01}}) {
      const InputDerivatives a = input_derivatives(f, m, s, z), n = input_derivatives_numeric(f, m, s, z);
      INFO(family_name(f) << " mean " << m << " std " << s);
      CHECK((a.dmean - n.dmean).cwiseAbs().maxCoeff() < 1e-6 * (1 + n.dmean.cwiseAbs().maxCoeff()));
      CHECK((a.dstd - n.dstd).cwiseAbs().maxCoeff() < 1e-6 * (1 + n.dstd.cwiseAbs().maxCoeff()));
    }
}

namespace {

const std::vector<Parameter> kParams{{"a.mean", 3, 7, 4.6}, {"a.std", 0.05, 1, 0.4}, {"b.mean", 1, 3, 2.2},
                                     {"b.std", 0.05, 1, 0.3}, {"c.mean", 0.5, 2, 1.1}, {"c.std", 0.05, 0.5, 0.2}};

/// y1 = a + b², y2 = 3a − b·c with its Jacobian; inputs a normal, b lognormal, c uniform.
StatisticalObjective make(MetricKind metric, const std::string& bandwidth = "silverman", Eigen::Index grid_nodes = 1001,
                          const std::vector<Parameter>& p = kParams) {
  std::vector<InputSpec> in{{"a", InputFamily::normal, 0, 0, 0, 1, {}}, {"b", InputFamily::lognormal, 0, 0, 2, 3, {}},
                            {"c", InputFamily::uniform, 0, 0, 4, 5, {}}};
  smi::Rng g(11);
  const Eigen::VectorXd a = g.normal_matrix(60, 1).col(0) * 0.3 + Eigen::VectorXd::Constant(60, 5.0);
  const Eigen::VectorXd b = g.normal_matrix(60, 1).col(0) * 0.2 + Eigen::VectorXd::Constant(60, 2.0);
  ResponseSpec r1, r2;
  r1.name = "y1";
  r1.data = (a.array() + b.array().square()).matrix();
  r2.name = "y2";
  r2.data = (3 * a.array() - b.array()).matrix();
  StatisticalOptions o;
  o.n = 400;
  o.grid_nodes = grid_nodes;
  o.metric = metric;
  o.bandwidth = bandwidth;
  o.seed = 5;
  auto model = [](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), 2);
    Y.col(0) = (X.col(0).array() + X.col(1).array().square()).matrix();
    Y.col(1) = (3 * X.col(0).array() - X.col(1).array() * X.col(2).array()).matrix();
    return Y;
  };
  StatisticalObjective f(in, {r1, r2}, p, model, o);
  f.set_model_jacobian([](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd J1 = Eigen::MatrixXd::Zero(X.rows(), 3), J2 = J1;
    J1.col(0).setOnes();
    J1.col(1) = 2 * X.col(1);
    J2.col(0).setConstant(3);
    J2.col(1) = -X.col(2);
    J2.col(2) = -X.col(1);
    return std::vector<Eigen::MatrixXd>{J1, J2};
  });
  return f;
}

}  // namespace

TEST_CASE("PR and loglik gradients agree with central differences of the objective") {
  for (MetricKind m : {MetricKind::pr, MetricKind::loglik})
    for (const char* bw : {"silverman", "scott", "robust", "mad"}) {
      const StatisticalObjective f = make(m, bw);
      REQUIRE(f.has_gradient());
      for (const Eigen::VectorXd& t : {Eigen::VectorXd((Eigen::VectorXd(6) << 4.6, 0.4, 2.2, 0.3, 1.1, 0.2).finished()),
                                       Eigen::VectorXd((Eigen::VectorXd(6) << 5.1, 0.25, 1.9, 0.15, 0.8, 0.3).finished())}) {
        Eigen::VectorXd g;
        const Evaluation e = f.value_and_gradient(t, g);
        CHECK(e.value == f(t).value);  // the same value as the plain objective
        const Eigen::VectorXd h = 1e-6 * Eigen::VectorXd::Ones(6);
        const Eigen::VectorXd fd = central_gradient(f, t, h);
        INFO((m == MetricKind::pr ? "pr" : "loglik") << " " << bw << "\nanalytic " << g.transpose() << "\ndifferences " << fd.transpose());
        // PR on a grid has kinks where fe − fp changes sign at a node; 1e-6 steps straddle few.
        CHECK((g - fd).cwiseAbs().maxCoeff() < 1e-4 * (1.0 + fd.cwiseAbs().maxCoeff()));
      }
    }
}

TEST_CASE("PR gradient on the blocked kernel sums (grid step <= h/4) and through a coarse grid agrees with central differences") {
  // 64001 nodes: steps far below h/16, the KDE summed on a coarser grid and interpolated
  // (kde_coarse_grid.hpp); 301 nodes: steps between h/16 and h/4, summed on the grid itself,
  // where the blocked chain's factors are largest (kde_uniform_grid.hpp).
  for (const auto& [nodes, coarse] : {std::pair<Eigen::Index, bool>{64001, true}, {301, false}}) {
    const StatisticalObjective f = make(MetricKind::pr, "silverman", nodes);
    const Eigen::VectorXd t = (Eigen::VectorXd(6) << 5.1, 0.25, 1.9, 0.15, 0.8, 0.3).finished();
    const Eigen::MatrixXd Y = f.predict(t);
    for (Eigen::Index j = 0; j < 2; ++j) {
      const smi::stats::Grid& g = *f.responses()[static_cast<std::size_t>(j)].grid;
      const double h = smi::stats::bandwidth_by_name(Y.col(j), "silverman");
      INFO(nodes << " nodes, response " << j << ": step h/" << h / g.step());
      REQUIRE(smi::stats::coarse_grid(g, h).has_value() == coarse);
      REQUIRE((coarse || (g.step() <= h / 4.0 && g.step() > h / 16.0)));
    }
    Eigen::VectorXd g;
    const Evaluation e = f.value_and_gradient(t, g);
    CHECK(e.value == f(t).value);
    const Eigen::VectorXd fd = central_gradient(f, t, 1e-6 * Eigen::VectorXd::Ones(6));
    INFO(nodes << " nodes\nanalytic " << g.transpose() << "\ndifferences " << fd.transpose());
    CHECK((g - fd).cwiseAbs().maxCoeff() < 1e-5 * (1.0 + fd.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("moment residuals: the chain-rule Jacobian agrees with forward differences; the moment start matches the data's moments") {
  const StatisticalObjective f = make(MetricKind::pr);
  StatisticalObjective nojac = f;
  nojac.set_model_jacobian({});
  const Eigen::VectorXd t = (Eigen::VectorXd(6) << 5.1, 0.25, 1.9, 0.15, 0.8, 0.3).finished();
  int runs = 0;
  Eigen::MatrixXd Ja, Jd;
  const Eigen::VectorXd ra = moment_residuals(f, t, &Ja, runs);
  CHECK(runs == 1);
  const Eigen::VectorXd rd = moment_residuals(nojac, t, &Jd, runs);
  CHECK(runs == 1 + 1 + 6);
  REQUIRE(ra.size() == 4);
  CHECK((ra - rd).norm() == 0.0);
  INFO("analytic\n" << Ja << "\ndifferences\n" << Jd);
  CHECK((Ja - Jd).cwiseAbs().maxCoeff() < 1e-4 * (1.0 + Jd.cwiseAbs().maxCoeff()));
  // From a start far off (objective near 2 per response), the moved start reproduces the data's
  // mean and sd of both responses (4 equations, 6 parameters).
  const Eigen::VectorXd far = (Eigen::VectorXd(6) << 3.5, 0.9, 2.8, 0.9, 1.9, 0.45).finished();
  const PreparedStart ps = moment_start(f, far);
  CHECK(ps.note.find("moment-matching") != std::string::npos);
  CHECK(f(ps.theta).value < f(far).value);
  const Eigen::MatrixXd Y = f.predict(ps.theta);
  for (Eigen::Index j = 0; j < 2; ++j) {
    const Eigen::VectorXd& d = f.responses()[static_cast<std::size_t>(j)].data;
    const double dm = d.mean(), ds = std::sqrt((d.array() - dm).square().sum() / static_cast<double>(d.size() - 1));
    const double ym = Y.col(j).mean(), ys = std::sqrt((Y.col(j).array() - ym).square().sum() / static_cast<double>(Y.rows() - 1));
    CHECK(ym == Approx(dm).epsilon(1e-6));
    CHECK(ys == Approx(ds).epsilon(1e-5));
  }
}

TEST_CASE("moment start with sds the bounds cannot reach: the constrained minimum of the mismatch, on a criterion") {
  // The data's sds (y1 about 0.85, y2 about 0.92) are below what the stds' lower bounds allow
  // (a.std >= 0.5 and b.std >= 0.3 give y1 an sd of 1.3 at least): the mismatch's minimum in the
  // box has the stds on their lower bounds (each input's spread only adds to the sds) and the
  // means trading the mean residuals against the sd ones. A full LM step projected on the box
  // crawled along the bounds there and stopped on its iteration budget.
  std::vector<Parameter> p = kParams;
  p[1].lower = 0.5, p[1].start = 0.7;
  p[3].lower = 0.3, p[3].start = 0.5;
  const StatisticalObjective f = make(MetricKind::pr, "silverman", 1001, p);
  const Eigen::VectorXd far = (Eigen::VectorXd(6) << 3.5, 0.9, 2.8, 0.9, 1.9, 0.45).finished();
  const PreparedStart ps = moment_start(f, far);
  // The reference minimum: SLSQP on the mismatch itself (central differences) with tight
  // tolerances from the same start.
  std::vector<Parameter> from = p;
  for (std::size_t i = 0; i < from.size(); ++i) from[i].start = far[static_cast<Eigen::Index>(i)];
  OptimizerOptions oo;
  oo.xtol_rel = 1e-10, oo.ftol_abs = 1e-12, oo.maxeval = 3000;
  const OptimizationResult ref = minimize(from, [&f](const Eigen::VectorXd& t) { return Evaluation{moment_mismatch(f, t), {}}; }, oo);
  INFO(ps.note << "\nstatus " << ps.status << " at " << ps.theta.transpose() << "\nreference " << ref.value << " at "
                << ref.theta.transpose() << " (" << ref.status << ")");
  CHECK((ps.status == "ftol_reached" || ps.status == "stationary"));
  const double reached = moment_mismatch(f, ps.theta);
  CHECK(ps.criterion_after == Approx(reached).epsilon(1e-12));
  CHECK(reached <= ref.value * (1.0 + 1e-3));
  for (Eigen::Index i : {1, 3, 5}) CHECK(ps.theta[i] == p[static_cast<std::size_t>(i)].lower);
}

TEST_CASE("no gradient for a custom metric, a data-driven bandwidth or a model without Jacobian") {
  StatisticalObjective f = make(MetricKind::pr, "sj");
  CHECK_FALSE(f.has_gradient());
  Eigen::VectorXd g;
  CHECK_THROWS_WITH(f.value_and_gradient(Eigen::VectorXd::Constant(6, 1.0), g), Catch::Contains("no analytic gradient"));
}

TEST_CASE("model differences: one batch of k + 1 (forward) or 2k + 1 (central) model passes gives the analytic gradient") {
  for (MetricKind m : {MetricKind::pr, MetricKind::loglik}) {
    const StatisticalObjective exact = make(m);
    StatisticalObjective fwd = exact, ctr = exact;
    fwd.set_model_jacobian({});
    ctr.set_model_jacobian({});
    REQUIRE_FALSE(fwd.has_gradient());
    fwd.set_model_differences(false, 1e-6);
    ctr.set_model_differences(true, 1e-5);
    REQUIRE(fwd.has_gradient());
    const Eigen::VectorXd t = (Eigen::VectorXd(6) << 5.1, 0.25, 1.9, 0.15, 0.8, 0.3).finished();
    Eigen::VectorXd ga, gf, gc;
    const long calls0 = fwd.model_runs(), passes0 = fwd.model_passes();
    const double vf = fwd.value_and_gradient(t, gf).value;
    CHECK(fwd.model_runs() - calls0 == 1);       // one model call: the batch
    CHECK(fwd.model_passes() - passes0 == 1 + 3);  // X and one step per calibrated input (3 inputs, 6 parameters)
    // The copies share the output cache (the same model and CRN): the outputs at X itself are
    // known now, so the central batch holds the 2k perturbed blocks only.
    const long cpass0 = ctr.model_passes();
    const double vc = ctr.value_and_gradient(t, gc).value;
    CHECK(ctr.model_passes() - cpass0 == 2 * 3);
    const double va = exact.value_and_gradient(t, ga).value;
    CHECK(vf == va);  // the batch's first block is the model at X itself
    CHECK(vc == va);
    // Against the objective's own central differences (the reference the issue names) and the
    // closed-form Jacobian's gradient.
    const Eigen::VectorXd fd = central_gradient(exact, t, 1e-6 * Eigen::VectorXd::Ones(6));
    INFO((m == MetricKind::pr ? "pr" : "loglik") << "\nanalytic " << ga.transpose() << "\nforward  " << gf.transpose() << "\ncentral  "
                                                  << gc.transpose() << "\nobjective differences " << fd.transpose());
    const double scale = 1.0 + fd.cwiseAbs().maxCoeff();
    CHECK((gf - fd).cwiseAbs().maxCoeff() < 1e-4 * scale);
    CHECK((gc - fd).cwiseAbs().maxCoeff() < 1e-4 * scale);
    CHECK((gf - ga).cwiseAbs().maxCoeff() < 1e-5 * scale);
    CHECK((gc - ga).cwiseAbs().maxCoeff() < 1e-7 * scale);
  }
}

TEST_CASE("a gradient where the value was just evaluated reuses its model outputs: k passes, not k + 1") {
  // SLSQP evaluates the value at a line-search trial and then asks for the gradient at the
  // accepted point (the same θ bit for bit): the base block of the model differences is known.
  StatisticalObjective f = make(MetricKind::pr);
  f.set_model_jacobian({});
  f.set_model_differences(false, 1e-6);
  const Eigen::VectorXd t = (Eigen::VectorXd(6) << 5.1, 0.25, 1.9, 0.15, 0.8, 0.3).finished();
  long runs = f.model_runs(), passes = f.model_passes();
  const double v = f(t).value;
  CHECK(f.model_runs() - runs == 1);
  CHECK(f.model_passes() - passes == 1);
  runs = f.model_runs();
  passes = f.model_passes();
  Eigen::VectorXd g, g_t;
  CHECK(f.value_and_gradient(t, g_t).value == v);
  CHECK(f.model_runs() - runs == 1);
  CHECK(f.model_passes() - passes == 3);  // the 3 perturbed blocks only
  // The same value again costs nothing; another θ costs its pass, and its gradient k + 1 when its
  // value was not asked first.
  passes = f.model_passes();
  CHECK(f(t).value == v);
  CHECK(f.model_passes() == passes);
  Eigen::VectorXd t2 = t;
  t2[0] += 1e-3;
  f.value_and_gradient(t2, g);
  CHECK(f.model_passes() - passes == 1 + 3);
  // A fresh objective (no outputs cached) gives the same gradient bit for bit: the cache changes
  // no number.
  StatisticalObjective fresh = make(MetricKind::pr);
  fresh.set_model_jacobian({});
  fresh.set_model_differences(false, 1e-6);
  Eigen::VectorXd g2;
  passes = fresh.model_passes();
  fresh.value_and_gradient(t, g2);
  CHECK(fresh.model_passes() - passes == 1 + 3);
  CHECK((g2 - g_t).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("model differences reject a step outside (0, 0.1)") {
  StatisticalObjective f = make(MetricKind::pr);
  CHECK_THROWS_WITH(f.set_model_differences(false, 0.0), Catch::Contains("model_step"));
  CHECK_THROWS_WITH(f.set_model_differences(false, 0.5), Catch::Contains("model_step"));
}

TEST_CASE("moment residuals on model differences: one model call, the analytic Jacobian's values") {
  const StatisticalObjective f = make(MetricKind::pr);
  StatisticalObjective diff = f;
  diff.set_model_jacobian({});
  diff.set_model_differences(false, 1e-6);
  const Eigen::VectorXd t = (Eigen::VectorXd(6) << 5.1, 0.25, 1.9, 0.15, 0.8, 0.3).finished();
  int ra = 0, rd = 0;
  Eigen::MatrixXd Ja, Jd;
  const long passes = diff.model_passes();
  const Eigen::VectorXd d = moment_residuals(diff, t, &Jd, rd);
  CHECK(rd == 1);                                 // one batch, not 1 + 6 predictions
  CHECK(diff.model_passes() - passes == 1 + 3);   // X and one block per calibrated input
  const Eigen::VectorXd a = moment_residuals(f, t, &Ja, ra);
  CHECK((a - d).norm() == 0.0);
  INFO("analytic\n" << Ja << "\nmodel differences\n" << Jd);
  CHECK((Ja - Jd).cwiseAbs().maxCoeff() < 1e-5 * (1.0 + Ja.cwiseAbs().maxCoeff()));
}
