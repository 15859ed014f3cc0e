// SPDX-License-Identifier: MIT
// Speed and accuracy of calibration, run by run_calibrate.sh beside SciPy's SLSQP
// with finite differences on the same objective (the CRN matrix, data and grids are written to
// a folder the peer reads). Prints "key value" lines: wall and CPU seconds, the optimiser's
// evaluations, objective evaluations, model runs and Jacobian runs, status, optimum.
//   bench_calibrate <dir> [quick|profile]   (quick: part 1 only; profile: part 2's cost per evaluation)
// 1. Analytic model, 4 parameters: a ~ N(μa, σa), b ~ N(μb, σb); y1 = a + b², y2 = 3a − b;
//    PR on fixed grids, n = 1000 CRN samples. Ours with the analytic gradient (tight, default
//    tolerances, with the moment-matching start), ours with central differences, and (in the
//    peer script) SciPy SLSQP with 2-point differences at several ftol.
// 2. A trial-2-like calibration: 10 parameters (5 inputs' means and stds), 2000 CRN samples, two
//    responses predicted by Kriging surrogates (150-point LHS designs of smooth functions), PR
//    on 4001-node grids, 4 starts side by side on 2 threads: analytic gradient (with and without
//    the moment start) against differences, and whether the starts agree where the data can tell.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <fmt/format.h>

#include <string>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/calibration.hpp"
#include "kernels/improve/overlap_start.hpp"
#include "kernels/improve/start_agreement.hpp"
#include "kernels/improve/statistical_objective.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "platform/core/rng.hpp"

using namespace smi::improve;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void write(const std::string& path, const Eigen::MatrixXd& m) {
  std::ofstream f(path);
  f.precision(17);
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) f << (j ? " " : "") << m(i, j);
    f << '\n';
  }
}

/// Jacobian runs of the bench's models (each a pass over the CRN sample like a model run).
std::atomic<long> g_jacobian_runs{0};
/// Calls of the objective's value-and-gradient (NLopt's SLSQP asks for a value alone at some points).
std::atomic<long> g_gradient_calls{0};

double process_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Run {
  OptimizationResult r;
  double seconds = 0.0;  ///< wall, best of the repetitions
  double cpu = 0.0;      ///< CPU seconds of all threads, of the best repetition
  long model_runs = 0, jacobian_runs = 0, gradient_calls = 0;
  /// Objective evaluations: the optimiser's (a value, or a value and its gradient) plus those made
  /// choosing the start; model runs = these + the moment start's steps.
  long objective_evaluations = 0;
};

/// Best of `reps` runs (the result and counts of the last).
Run timed(int reps, const std::vector<Parameter>& p, const Objective& f, const OptimizerOptions& o, const StatisticalObjective& obj) {
  Run out;
  out.seconds = 1e300;
  for (int i = 0; i < reps; ++i) {
    const long m0 = obj.model_runs(), j0 = g_jacobian_runs.load(), q0 = g_gradient_calls.load();
    const double t0 = now(), c0 = process_cpu();
    out.r = minimize(p, f, o);
    const double w = now() - t0, c = process_cpu() - c0;
    if (w < out.seconds) out.seconds = w, out.cpu = c;
    out.model_runs = obj.model_runs() - m0;
    out.jacobian_runs = g_jacobian_runs.load() - j0;
    out.gradient_calls = g_gradient_calls.load() - q0;
  }
  // Every gradient call ran the Jacobian once; the other Jacobian runs are the moment start's
  // steps, each with one model run; every other model run is an objective evaluation (one that ran
  // the model: at a point whose outputs the objective has cached, a gradient runs none).
  out.objective_evaluations = out.model_runs - (out.jacobian_runs - out.gradient_calls);
  return out;
}

void report(const char* key, const Run& run) {
  std::printf("%s_gradient_calls %ld\n", key, run.gradient_calls);
  std::printf("%s_time %.6f\n%s_cpu %.6f\n%s_evals %d\n%s_objective_evals %ld\n%s_model_runs %ld\n%s_jacobian_runs %ld\n%s_status %s\n%s_value %.12g\n%s_theta",
              key, run.seconds, key, run.cpu, key, run.r.evaluations, key, run.objective_evaluations, key, run.model_runs, key,
              run.jacobian_runs, key, run.r.status.c_str(), key, run.r.value, key);
  for (Eigen::Index i = 0; i < run.r.theta.size(); ++i) std::printf(" %.10g", run.r.theta[i]);
  std::printf("\n");
}

/// Part 1's problems. Two inputs (4 parameters): a ~ N(5, 0.3), b ~ N(2, 0.2) observed through
/// y1 = a + b², y2 = 3a − b (60 data each). Four inputs (8 parameters): the same a, b, y1, y2 and
/// c ~ N(4, 0.25), d ~ N(1.5, 0.15) through y3 = c + d², y4 = 3c − d + a/2 (coupled to a, so not
/// two independent copies). Each response's mean and spread are the data's; the pairs' four
/// moments fix each pair's four parameters, so every parameter is identifiable. The analytic
/// model and its Jacobian (counted).
struct AnalyticProblem {
  int inputs = 2;
  std::vector<ResponseSpec> r;
  std::vector<Parameter> p{{"a.mean", 3, 7, 4.2}, {"a.std", 0.05, 1, 0.6}, {"b.mean", 1, 3, 2.4}, {"b.std", 0.05, 1, 0.5}};
  std::vector<InputSpec> in{{"a", InputFamily::normal, 0, 0, 0, 1, {}}, {"b", InputFamily::normal, 0, 0, 2, 3, {}}};
  StatisticalOptions so;

  explicit AnalyticProblem(int k) : inputs(k) {
    smi::Rng g(2026);
    Eigen::MatrixXd X(60, k);
    X.col(0) = g.normal(60, 5.0, 0.3);
    X.col(1) = g.normal(60, 2.0, 0.2);
    if (k == 4) {
      X.col(2) = g.normal(60, 4.0, 0.25);
      X.col(3) = g.normal(60, 1.5, 0.15);
      p.insert(p.end(), {{"c.mean", 2, 6, 3.4}, {"c.std", 0.05, 1, 0.5}, {"d.mean", 0.5, 2.5, 1.9}, {"d.std", 0.05, 1, 0.4}});
      in.insert(in.end(), {{"c", InputFamily::normal, 0, 0, 4, 5, {}}, {"d", InputFamily::normal, 0, 0, 6, 7, {}}});
    }
    const Eigen::MatrixXd Y = model(X);
    for (Eigen::Index j = 0; j < Y.cols(); ++j) {
      ResponseSpec rs;
      rs.name = fmt::format("y{}", j + 1);
      rs.data = Y.col(j);
      r.push_back(rs);
    }
    so.n = 1000;
    so.grid_nodes = 2001;
    so.seed = 1;
  }

  static Eigen::MatrixXd model(const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), X.cols());
    Y.col(0) = (X.col(0).array() + X.col(1).array().square()).matrix();
    Y.col(1) = (3 * X.col(0).array() - X.col(1).array()).matrix();
    if (X.cols() == 4) {
      Y.col(2) = (X.col(2).array() + X.col(3).array().square()).matrix();
      Y.col(3) = (3 * X.col(2).array() - X.col(3).array() + 0.5 * X.col(0).array()).matrix();
    }
    return Y;
  }

  static std::vector<Eigen::MatrixXd> jacobian(const Eigen::MatrixXd& X) {
    ++g_jacobian_runs;
    const Eigen::Index k = X.cols();
    std::vector<Eigen::MatrixXd> J(static_cast<std::size_t>(k), Eigen::MatrixXd::Zero(X.rows(), k));
    J[0].col(0).setOnes();
    J[0].col(1) = 2 * X.col(1);
    J[1].col(0).setConstant(3);
    J[1].col(1).setConstant(-1);
    if (k == 4) {
      J[2].col(2).setOnes();
      J[2].col(3) = 2 * X.col(3);
      J[3].col(2).setConstant(3);
      J[3].col(3).setConstant(-1);
      J[3].col(0).setConstant(0.5);
    }
    return J;
  }
};

/// The objective's value and analytic gradient as the optimiser's gradient, counting its calls.
ObjectiveGradient counted_gradient(const StatisticalObjective& obj) {
  return [&obj](const Eigen::VectorXd& t, Eigen::VectorXd& gr) {
    ++g_gradient_calls;
    return obj.value_and_gradient(t, gr);
  };
}

/// Part 1's runs on a problem whose keys end in `tag` (its parameter count): tight tolerances
/// (analytic, differences), then smi.calibrate's defaults (xtol_rel 1e-6, ftol_abs 1e-8)
/// analytic, with the moment-matching start (Levenberg-Marquardt on the responses' means and
/// sds), with that start and a looser xtol_rel (1e-4 of the scaled box), and by differences;
/// then SLSQP at xtol_rel 1e-4 alone, and L-BFGS (method = "lbfgs") at both tolerances, with and
/// without the moment start.
void run_analytic_problem(const AnalyticProblem& ap, const StatisticalObjective& obj) {
  const std::vector<Parameter>& p = ap.p;
  const std::string tag = std::to_string(p.size());
  auto key = [&tag](const char* name) { return fmt::format(fmt::runtime(name), tag); };
  {  // the analytic gradient against central differences at the start (a check of the bench's Jacobian)
    Eigen::VectorXd t0(static_cast<Eigen::Index>(p.size())), h(t0.size()), gr;
    for (std::size_t i = 0; i < p.size(); ++i) t0[static_cast<Eigen::Index>(i)] = p[i].start, h[static_cast<Eigen::Index>(i)] = 1e-5 * (p[i].upper - p[i].lower);
    obj.value_and_gradient(t0, gr);
    const Eigen::VectorXd fd = central_gradient([&obj](const Eigen::VectorXd& t) { return obj(t); }, t0, h);
    std::printf("%s %.3g\n", key("gradient_check{}").c_str(), (gr - fd).cwiseAbs().maxCoeff() / fd.cwiseAbs().maxCoeff());
  }
  Objective f = [&obj](const Eigen::VectorXd& t) { return obj(t); };
  OptimizerOptions o;
  o.xtol_rel = 1e-10;
  o.ftol_abs = 1e-12;
  o.maxeval = 4000;
  OptimizerOptions oa = o;
  oa.gradient = counted_gradient(obj);
  report(key("analytic{}").c_str(), timed(3, p, f, oa, obj));
  report(key("differences{}").c_str(), timed(1, p, f, o, obj));
  OptimizerOptions od;
  od.gradient = oa.gradient;
  report(key("analytic{}default").c_str(), timed(3, p, f, od, obj));
  od.prepare_start = [&obj](const Eigen::VectorXd& t) { return moment_start(obj, t); };
  report(key("analytic{}moments").c_str(), timed(3, p, f, od, obj));
  OptimizerOptions ol = od;
  ol.xtol_rel = 1e-4;
  report(key("analytic{}momentsloose").c_str(), timed(3, p, f, ol, obj));
  od.gradient = {};
  od.prepare_start = {};
  report(key("differences{}default").c_str(), timed(1, p, f, od, obj));
  OptimizerOptions os;  // SLSQP at xtol_rel 1e-4 without the moment start
  os.gradient = oa.gradient;
  os.xtol_rel = 1e-4;
  report(key("analytic{}loose").c_str(), timed(3, p, f, os, obj));
  OptimizerOptions ob;  // L-BFGS (method = "lbfgs"): default tolerances, then xtol_rel 1e-4, each without and with the moment start
  ob.method = Method::lbfgs;
  ob.gradient = oa.gradient;
  report(key("lbfgs{}default").c_str(), timed(3, p, f, ob, obj));
  ob.prepare_start = ol.prepare_start;
  report(key("lbfgs{}moments").c_str(), timed(3, p, f, ob, obj));
  ob.xtol_rel = 1e-4;
  ob.prepare_start = {};
  report(key("lbfgs{}loose").c_str(), timed(3, p, f, ob, obj));
  ob.prepare_start = ol.prepare_start;
  report(key("lbfgs{}momentsloose").c_str(), timed(3, p, f, ob, obj));
  // Looser still, as SciPy is run at looser ftol too: each side's cheapest run within 1e-4 of the
  // tight optimum is compared, whatever tolerance got it there.
  for (const double x : {3e-4, 1e-3}) {
    ol.xtol_rel = ob.xtol_rel = x;
    report(fmt::format("analytic{}moments_x{:g}", tag, x).c_str(), timed(3, p, f, ol, obj));
    report(fmt::format("lbfgs{}moments_x{:g}", tag, x).c_str(), timed(3, p, f, ob, obj));
  }
}

/// What the SciPy peer reads, in <dir>/p<parameters>/: the CRN matrix, the data (y<j>.txt), the
/// grids (lo, hi, nodes per response) and the box (lower, upper, start per parameter).
void write_peer_files(const std::string& dir, const AnalyticProblem& ap, const StatisticalObjective& obj) {
  const std::string d = fmt::format("{}/p{}", dir, ap.p.size());
  std::filesystem::create_directories(d);
  write(d + "/z.txt", obj.crn());
  const Eigen::Index R = static_cast<Eigen::Index>(ap.r.size()), k = static_cast<Eigen::Index>(ap.p.size());
  Eigen::MatrixXd grids(R, 3), box(k, 3);
  for (Eigen::Index j = 0; j < R; ++j) {
    const auto& g = *obj.responses()[static_cast<std::size_t>(j)].grid;
    write(fmt::format("{}/y{}.txt", d, j + 1), ap.r[static_cast<std::size_t>(j)].data);
    grids.row(j) << g.lo, g.hi, static_cast<double>(g.n);
  }
  for (Eigen::Index i = 0; i < k; ++i) box.row(i) << ap.p[static_cast<std::size_t>(i)].lower, ap.p[static_cast<std::size_t>(i)].upper, ap.p[static_cast<std::size_t>(i)].start;
  write(d + "/grids.txt", grids);
  write(d + "/box.txt", box);
}

/// Part 2's problem: 5 inputs in a box, two smooth responses with Kriging surrogates fitted on a
/// 150-point random design, 40 synthetic data from the true functions at the true distributions,
/// and 10 parameters (each input's mean and std) with starts off the truth.
struct TrialProblem {
  static constexpr int k = 5;
  smi::surrogate::kriging::Model k1, k2;
  ResponseSpec r1, r2;
  std::vector<Parameter> p;
  std::vector<InputSpec> in;
  StatisticalOptions so;

  static Eigen::VectorXd f1(const Eigen::MatrixXd& X) {
    return Eigen::VectorXd((X.col(0).array() * X.col(1).array() + X.col(2).array().sqrt() * 2 + X.col(3).array() * X.col(4).array()).matrix());
  }
  static Eigen::VectorXd f2(const Eigen::MatrixXd& X) {
    return Eigen::VectorXd((X.col(1).array() / X.col(2).array() * 10 + X.col(4).array().log() * 3 - X.col(0).array() * X.col(3).array()).matrix());
  }

  /// n, crn and bw: the CRN sample size and kind and the predicted KDEs' bandwidth rule (the
  /// study's: 2000, random, silverman); data: the synthetic observations per response (40, the
  /// study's experiments). The variants ask whether the starts' disagreement is the CRN
  /// objective's roughness or the 40-point data's.
  explicit TrialProblem(Eigen::Index n = 2000, CrnKind crn = CrnKind::random, const std::string& bw = "silverman", Eigen::Index data = 40) {
    Eigen::MatrixXd lo(1, k), hi(1, k);
    lo << 0.5, 1.0, 2.0, 0.2, 3.0;
    hi << 1.5, 3.0, 4.0, 0.8, 7.0;
    smi::Rng g(7);
    const Eigen::MatrixXd U = g.uniform_matrix(150, k);
    Eigen::MatrixXd D(150, k);
    for (int j = 0; j < k; ++j) D.col(j) = (lo(0, j) + (hi(0, j) - lo(0, j)) * U.col(j).array()).matrix();
    smi::surrogate::kriging::FitOptions fo;
    k1 = smi::surrogate::kriging::fit(D, f1(D), fo);
    k2 = smi::surrogate::kriging::fit(D, f2(D), fo);
    // Truth and synthetic data (the true functions, not the surrogates).
    Eigen::VectorXd mu(k), sd(k);
    mu << 1.0, 2.0, 3.0, 0.5, 5.0;
    sd << 0.08, 0.15, 0.2, 0.04, 0.4;
    Eigen::MatrixXd Xd(data, k);
    for (int j = 0; j < k; ++j) Xd.col(j) = g.normal(data, mu[j], sd[j]);
    r1.name = "mode1";
    r1.data = f1(Xd);
    r2.name = "mode4";
    r2.data = f2(Xd);
    for (int j = 0; j < k; ++j) {
      const double span = hi(0, j) - lo(0, j);
      p.push_back({fmt::format("x{}.mean", j + 1), lo(0, j) + 0.2 * span, hi(0, j) - 0.2 * span, mu[j] + 0.1 * span});
      p.push_back({fmt::format("x{}.std", j + 1), 0.01 * span, 0.25 * span, 0.1 * span});
      in.push_back({fmt::format("x{}", j + 1), InputFamily::normal, 0, 0, 2 * j, 2 * j + 1, {}});
    }
    so.n = n;
    so.crn = crn;
    so.bandwidth = bw;
    so.grid_nodes = 4001;
    so.seed = 3;
    so.threads = 1;  // one thread per evaluation: the starts run side by side instead
  }
};

/// Cost of one evaluation's parts at the start, CPU seconds of one thread (best of 30 each;
/// the thread's CPU time is steadier than wall time on a shared machine).
void profile_evaluation(const TrialProblem& tp, const StatisticalObjective& obj, const Model& model) {
  Eigen::VectorXd t0(static_cast<Eigen::Index>(tp.p.size()));
  for (std::size_t i = 0; i < tp.p.size(); ++i) t0[static_cast<Eigen::Index>(i)] = tp.p[i].start;
  auto best = [](auto&& fn) {
    double b = 1e300;
    for (int r = 0; r < 30; ++r) {
      const double a = cpu_now();
      fn();
      b = std::min(b, cpu_now() - a);
    }
    return b;
  };
  const Eigen::MatrixXd X = obj.inputs_at(t0);
  std::printf("profile_inputs %.6f\n", best([&] { (void)obj.inputs_at(t0); }));
  std::printf("profile_model %.6f\n", best([&] { (void)model(X); }));
  std::printf("profile_jacobian %.6f\n", best([&] {
    (void)smi::surrogate::kriging::predict_gradient(tp.k1, X, 1);
    (void)smi::surrogate::kriging::predict_gradient(tp.k2, X, 1);
  }));
  std::printf("profile_value %.6f\n", best([&] { (void)obj(t0); }));
  Eigen::VectorXd gr;
  std::printf("profile_value_and_gradient %.6f\n", best([&] { (void)obj.value_and_gradient(t0, gr); }));
}

/// smi.calibrate's own near-optimal tolerance for this objective (calibration.hpp: PR 0.01 per
/// response), read from the pipeline rather than restated here.
double pipeline_tolerance(const StatisticalObjective& obj, double value) {
  CalibrationProblem p;
  p.responses = obj.responses();
  p.stat = obj.options();
  p.model = [](const Eigen::MatrixXd& X) { return X; };
  return near_optimal_tolerance(p, CalibrationOptions{}, value).first;
}

/// A multistart run's report plus agreement where the data can tell: the starts whose objective
/// is within the near-optimal tolerance of the best (smi.calibrate's PR default, 0.01 per
/// response) and the largest difference of their predicted responses' summaries (four
/// standardised Hermite moments per response, unit variance per datum: differences far below
/// 1/sqrt(40) are invisible to the data).
void report_agreement(const char* key, const Run& run, const StatisticalObjective& obj, const std::vector<Parameter>& params) {
  report(key, run);
  std::printf("%s_agree %d\n%s_optima %zu\n%s_converged_starts", key, run.r.starts_agree ? 1 : 0, key, run.r.optima.size(), key);
  for (const auto& st : run.r.starts) std::printf(" %s", st.status.c_str());
  std::printf("\n%s_start_values", key);
  for (const auto& st : run.r.starts) std::printf(" %.8f", st.value);
  const Eigen::VectorXd best = obj.summaries(run.r.theta);
  int near = 0;
  double gap = 0.0, dsum = 0.0;
  const double tolerance = pipeline_tolerance(obj, run.r.value);
  for (const auto& st : run.r.starts) {
    if (st.value - run.r.value > tolerance) continue;
    ++near;
    gap = std::max(gap, st.value - run.r.value);
    dsum = std::max(dsum, (obj.summaries(st.theta) - best).cwiseAbs().maxCoeff());
  }
  std::printf("\n%s_near %d\n%s_near_gap %.3g\n%s_near_summary_diff %.3g\n", key, near, key, gap, key, dsum);
  // smi.calibrate's own account (start_agreement.hpp) at its PR default tolerance, 0.01 per response
  const StartAgreement a = start_agreement(params, [&obj](const Eigen::VectorXd& t) { return obj(t); }, run.r, tolerance, prediction_check(obj));
  std::printf("%s_same %d\n%s_largest_gap %.4g\n%s_largest_barrier %.4g\n%s_largest_prediction_distance %.4g\n", key, a.same, key,
              a.largest_gap, key, a.largest_barrier, key, a.largest_prediction_distance);
}

/// Part 2's starts, the same for every run and variant: 4 starts (the study's budget of 300
/// each), seed 11, side by side on 2 threads.
OptimizerOptions trial_starts() {
  OptimizerOptions o;
  o.multistart = 4;
  o.seed = 11;
  o.maxeval = 300;
  o.start_threads = 2;
  return o;
}

/// Part 2's runs: 4 starts (the study's budget of 300 each) side by side on 2 threads (model,
/// KDE and Jacobian on one thread each), analytic, analytic with the moment start, differences.
void run_trial_problem(const TrialProblem& tp, const StatisticalObjective& obj) {
  Objective f = [&obj](const Eigen::VectorXd& t) { return obj(t); };
  const OptimizerOptions o = trial_starts();
  OptimizerOptions oa = o;
  oa.gradient = counted_gradient(obj);
  OptimizerOptions om = oa;
  om.prepare_start = [&obj](const Eigen::VectorXd& t) { return moment_start(obj, t); };
  report_agreement("trial_analytic", timed(1, tp.p, f, oa, obj), obj, tp.p);
  report_agreement("trial_moments", timed(1, tp.p, f, om, obj), obj, tp.p);
  report_agreement("trial_differences", timed(1, tp.p, f, o, obj), obj, tp.p);
}

/// Part 2's objective: the two Kriging predictors as the model (one thread each) and their
/// closed-form Jacobians (counted); `seed` the CRN seed.
struct TrialObjective {
  Model model;
  StatisticalObjective obj;
  static StatisticalOptions with(StatisticalOptions so, std::uint64_t seed, MetricKind metric) {
    so.seed = seed;
    so.metric = metric;
    return so;
  }
  TrialObjective(const TrialProblem& tp, std::uint64_t seed, MetricKind metric = MetricKind::pr)
      : model([&tp](const Eigen::MatrixXd& X) {
          Eigen::MatrixXd Y(X.rows(), 2);
          Y.col(0) = smi::surrogate::kriging::predict_mean(tp.k1, X, tp.so.threads);
          Y.col(1) = smi::surrogate::kriging::predict_mean(tp.k2, X, tp.so.threads);
          return Y;
        }),
        obj(tp.in, {tp.r1, tp.r2}, tp.p, model, with(tp.so, seed, metric)) {
    obj.set_model_jacobian([&tp](const Eigen::MatrixXd& X) {
      ++g_jacobian_runs;
      return std::vector<Eigen::MatrixXd>{smi::surrogate::kriging::predict_gradient(tp.k1, X, tp.so.threads),
                                          smi::surrogate::kriging::predict_gradient(tp.k2, X, tp.so.threads)};
    });
  }
};

/// One variant of part 2 (CRN kind, n, bandwidth, CRN seed, data, metric, method): the analytic run with 4 starts,
/// and each start's optimum, so the peer can tell whether the starts agree.
void run_trial_variant(const char* key, const TrialProblem& tp, const StatisticalObjective& obj, Method method, int hops = 0,
                       double hop_step = 0.2) {
  Objective f = [&obj](const Eigen::VectorXd& t) { return obj(t); };
  OptimizerOptions o = trial_starts();
  o.method = method;
  o.hops = hops;
  o.hop_step = hop_step;
  o.gradient = counted_gradient(obj);
  report_agreement(key, timed(1, tp.p, f, o, obj), obj, tp.p);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  const std::string mode = argc > 2 ? argv[2] : "";
  if (mode != "profile" && mode != "variants") {  // 1. analytic models, 4 and 8 parameters
    for (const int k : {2, 4}) {
      const AnalyticProblem ap(k);
      StatisticalObjective obj(ap.in, ap.r, ap.p, &AnalyticProblem::model, ap.so);
      obj.set_model_jacobian(&AnalyticProblem::jacobian);
      run_analytic_problem(ap, obj);
      write_peer_files(dir, ap, obj);
    }
  }
  if (mode == "variants") {  // 2'. the trial problem's variants: <dir> variants <name>
    // (quantiles, random2000seed, random8000, quantiles8000, data1000, loglik, lbfgs, or a bandwidth rule)
    const std::string v = argc > 3 ? argv[3] : "quantiles";
    const TrialProblem tp = v == "quantiles" ? TrialProblem(2000, CrnKind::quantiles)
                            : v == "random8000" ? TrialProblem(8000)
                            : v == "quantiles8000" ? TrialProblem(8000, CrnKind::quantiles)
                            : v == "random2000seed" ? TrialProblem(2000)
                            : v == "data1000" ? TrialProblem(2000, CrnKind::random, "silverman", 1000)
                            : v == "loglik" || v == "lbfgs" || v.rfind("hops", 0) == 0 ? TrialProblem(2000)
                                                  : TrialProblem(2000, CrnKind::random, v);
    const TrialObjective to(tp, v == "random2000seed" ? 4 : tp.so.seed, v == "loglik" ? MetricKind::loglik : MetricKind::pr);
    // hops<N>[_<step>]: basin hopping, N hops of up to ±step (default 0.2) per start
    const bool hopping = v.rfind("hops", 0) == 0;
    const int hops = hopping ? std::stoi(v.substr(4)) : 0;
    const double step = hopping && v.find('_') != std::string::npos ? std::stod(v.substr(v.find('_') + 1)) : 0.2;
    run_trial_variant(("variant_" + v).c_str(), tp, to.obj, v == "lbfgs" ? Method::lbfgs : Method::slsqp, hops, step);
    return 0;
  }
  if (mode != "quick") {  // 2. trial-2-like: 10 parameters, 2000 CRN samples, Kriging outputs
    const TrialProblem tp;
    const TrialObjective to(tp, tp.so.seed);
    if (mode == "profile") {
      profile_evaluation(tp, to.obj, to.model);
      return 0;
    }
    run_trial_problem(tp, to.obj);
  }
  return 0;
}
