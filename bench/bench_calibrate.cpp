// Speed and accuracy of calibration (issue 11), run by run_calibrate.sh beside SciPy's SLSQP
// with finite differences on the same objective (the CRN matrix, data and grids are written to
// a folder the peer reads). Prints "key value" lines.
//   bench_calibrate <dir> [quick]   (quick: part 1 only)
// 1. Analytic model, 4 parameters: a ~ N(μa, σa), b ~ N(μb, σb); y1 = a + b², y2 = 3a − b;
//    PR on fixed grids, n = 1000 CRN samples. Ours with the analytic gradient, ours with
//    central differences, and (in the peer script) SciPy SLSQP with 2-point differences.
// 2. A trial-2-like calibration: 10 parameters (5 inputs' means and stds), 2000 CRN samples, two
//    responses predicted by Kriging surrogates (150-point LHS designs of smooth functions), PR
//    on 4001-node grids, 4 starts: analytic gradient against differences.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <fmt/format.h>

#include <string>

#include "kernels/core/rng.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/statistical_objective.hpp"
#include "kernels/surrogate/kriging.hpp"

using namespace smi::improve;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

void write(const std::string& path, const Eigen::MatrixXd& m) {
  std::ofstream f(path);
  f.precision(17);
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) f << (j ? " " : "") << m(i, j);
    f << '\n';
  }
}

struct Run {
  OptimizationResult r;
  double seconds = 0.0;
};

/// Best of `reps` runs (the result of the last).
Run timed(int reps, const std::vector<Parameter>& p, const Objective& f, const OptimizerOptions& o) {
  Run out;
  out.seconds = 1e300;
  for (int i = 0; i < reps; ++i) {
    const double t0 = now();
    out.r = minimize(p, f, o);
    out.seconds = std::min(out.seconds, now() - t0);
  }
  return out;
}

void report(const char* key, const Run& run) {
  std::printf("%s_time %.6f\n%s_evals %d\n%s_status %s\n%s_value %.12g\n%s_theta", key, run.seconds, key, run.r.evaluations, key,
              run.r.status.c_str(), key, run.r.value, key);
  for (Eigen::Index i = 0; i < run.r.theta.size(); ++i) std::printf(" %.10g", run.r.theta[i]);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  // ---- 1. analytic model, 4 parameters
  {
    smi::Rng g(2026);
    const Eigen::VectorXd a = g.normal(60, 5.0, 0.3), b = g.normal(60, 2.0, 0.2);
    ResponseSpec r1, r2;
    r1.name = "y1";
    r1.data = (a.array() + b.array().square()).matrix();
    r2.name = "y2";
    r2.data = (3 * a.array() - b.array()).matrix();
    std::vector<Parameter> p{{"a.mean", 3, 7, 4.2}, {"a.std", 0.05, 1, 0.6}, {"b.mean", 1, 3, 2.4}, {"b.std", 0.05, 1, 0.5}};
    std::vector<InputSpec> in{{"a", InputFamily::normal, 0, 0, 0, 1}, {"b", InputFamily::normal, 0, 0, 2, 3}};
    StatisticalOptions so;
    so.n = 1000;
    so.grid_nodes = 2001;
    so.seed = 1;
    auto model = [](const Eigen::MatrixXd& X) {
      Eigen::MatrixXd Y(X.rows(), 2);
      Y.col(0) = (X.col(0).array() + X.col(1).array().square()).matrix();
      Y.col(1) = (3 * X.col(0).array() - X.col(1).array()).matrix();
      return Y;
    };
    StatisticalObjective obj(in, {r1, r2}, p, model, so);
    obj.set_model_jacobian([](const Eigen::MatrixXd& X) {
      Eigen::MatrixXd J1 = Eigen::MatrixXd::Zero(X.rows(), 2), J2 = J1;
      J1.col(0).setOnes();
      J1.col(1) = 2 * X.col(1);
      J2.col(0).setConstant(3);
      J2.col(1).setConstant(-1);
      return std::vector<Eigen::MatrixXd>{J1, J2};
    });
    Objective f = [&obj](const Eigen::VectorXd& t) { return obj(t); };
    OptimizerOptions o;
    o.xtol_rel = 1e-10;
    o.ftol_abs = 1e-12;
    o.maxeval = 2000;
    OptimizerOptions oa = o;
    oa.gradient = [&obj](const Eigen::VectorXd& t, Eigen::VectorXd& gr) { return obj.value_and_gradient(t, gr); };
    report("analytic4", timed(3, p, f, oa));
    report("differences4", timed(1, p, f, o));
    // The default tolerances of smi.calibrate (xtol_rel 1e-6, ftol_abs 1e-8).
    OptimizerOptions od;
    od.gradient = oa.gradient;
    report("analytic4default", timed(3, p, f, od));
    od.gradient = {};
    report("differences4default", timed(1, p, f, od));
    write(dir + "/z.txt", obj.crn());
    write(dir + "/y1.txt", r1.data);
    write(dir + "/y2.txt", r2.data);
    Eigen::MatrixXd grids(2, 3), box(4, 3);
    for (int j = 0; j < 2; ++j) grids.row(j) << obj.responses()[j].grid->lo, obj.responses()[j].grid->hi, static_cast<double>(obj.responses()[j].grid->n);
    for (int i = 0; i < 4; ++i) box.row(i) << p[i].lower, p[i].upper, p[i].start;
    write(dir + "/grids.txt", grids);
    write(dir + "/box.txt", box);
  }
  // ---- 2. trial-2-like: 10 parameters, 2000 CRN samples, Kriging outputs
  if (!(argc > 2 && std::string(argv[2]) == "quick")) {
    const int k = 5;
    Eigen::MatrixXd lo(1, k), hi(1, k);
    lo << 0.5, 1.0, 2.0, 0.2, 3.0;
    hi << 1.5, 3.0, 4.0, 0.8, 7.0;
    smi::Rng g(7);
    const Eigen::MatrixXd U = g.uniform_matrix(150, k);
    Eigen::MatrixXd D(150, k);
    for (int j = 0; j < k; ++j) D.col(j) = (lo(0, j) + (hi(0, j) - lo(0, j)) * U.col(j).array()).matrix();
    auto f1 = [](const Eigen::MatrixXd& X) {
      return Eigen::VectorXd((X.col(0).array() * X.col(1).array() + X.col(2).array().sqrt() * 2 + X.col(3).array() * X.col(4).array()).matrix());
    };
    auto f2 = [](const Eigen::MatrixXd& X) {
      return Eigen::VectorXd((X.col(1).array() / X.col(2).array() * 10 + X.col(4).array().log() * 3 - X.col(0).array() * X.col(3).array()).matrix());
    };
    smi::surrogate::kriging::FitOptions fo;
    const smi::surrogate::kriging::Model k1 = smi::surrogate::kriging::fit(D, f1(D), fo), k2 = smi::surrogate::kriging::fit(D, f2(D), fo);
    // Truth and synthetic data (the true functions, not the surrogates).
    Eigen::VectorXd mu(k), sd(k);
    mu << 1.0, 2.0, 3.0, 0.5, 5.0;
    sd << 0.08, 0.15, 0.2, 0.04, 0.4;
    Eigen::MatrixXd Xd(40, k);
    for (int j = 0; j < k; ++j) Xd.col(j) = g.normal(40, mu[j], sd[j]);
    ResponseSpec r1, r2;
    r1.name = "mode1";
    r1.data = f1(Xd);
    r2.name = "mode4";
    r2.data = f2(Xd);
    std::vector<Parameter> p;
    std::vector<InputSpec> in;
    for (int j = 0; j < k; ++j) {
      const double span = hi(0, j) - lo(0, j);
      p.push_back({fmt::format("x{}.mean", j + 1), lo(0, j) + 0.2 * span, hi(0, j) - 0.2 * span, mu[j] + 0.1 * span});
      p.push_back({fmt::format("x{}.std", j + 1), 0.01 * span, 0.25 * span, 0.1 * span});
      in.push_back({fmt::format("x{}", j + 1), InputFamily::normal, 0, 0, 2 * j, 2 * j + 1});
    }
    StatisticalOptions so;
    so.n = 2000;
    so.grid_nodes = 4001;
    so.seed = 3;
    so.threads = 2;
    auto model = [&](const Eigen::MatrixXd& X) {
      Eigen::MatrixXd Y(X.rows(), 2);
      Y.col(0) = smi::surrogate::kriging::predict_mean(k1, X, 2);
      Y.col(1) = smi::surrogate::kriging::predict_mean(k2, X, 2);
      return Y;
    };
    StatisticalObjective obj(in, {r1, r2}, p, model, so);
    obj.set_model_jacobian([&](const Eigen::MatrixXd& X) {
      return std::vector<Eigen::MatrixXd>{smi::surrogate::kriging::predict_gradient(k1, X, 2), smi::surrogate::kriging::predict_gradient(k2, X, 2)};
    });
    Objective f = [&obj](const Eigen::VectorXd& t) { return obj(t); };
    OptimizerOptions o;
    o.multistart = 4;
    o.seed = 11;
    o.maxeval = 300;  // the study's budget per start
    OptimizerOptions oa = o;
    oa.gradient = [&obj](const Eigen::VectorXd& t, Eigen::VectorXd& gr) { return obj.value_and_gradient(t, gr); };
    const Run an = timed(1, p, f, oa);
    report("trial_analytic", an);
    std::printf("trial_analytic_agree %d\ntrial_analytic_optima %zu\ntrial_analytic_converged_starts", an.r.starts_agree ? 1 : 0, an.r.optima.size());
    for (const auto& s : an.r.starts) std::printf(" %s", s.status.c_str());
    std::printf("\n");
    const Run fd = timed(1, p, f, o);
    report("trial_differences", fd);
    std::printf("trial_differences_agree %d\ntrial_differences_optima %zu\ntrial_differences_converged_starts", fd.r.starts_agree ? 1 : 0,
                fd.r.optima.size());
    for (const auto& s : fd.r.starts) std::printf(" %s", s.status.c_str());
    std::printf("\n");
    for (const auto& s : an.r.starts) {
      std::printf("trial_analytic_start_value %.10g", s.value);
      for (Eigen::Index i = 0; i < s.theta.size(); ++i) std::printf(" %.6g", s.theta[i]);
      std::printf("\n");
    }
  }
  return 0;
}
