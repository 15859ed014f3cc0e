// SPDX-License-Identifier: MIT
#include "kernels/improve/bounded_optimizer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <nlopt.hpp>

#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::improve {

Method parse_method(std::string_view name) {
  if (name == "slsqp" || name == "sqp") return Method::slsqp;
  if (name == "lbfgs" || name == "l-bfgs") return Method::lbfgs;
  if (name == "cobyla") return Method::cobyla;
  if (name == "bobyqa") return Method::bobyqa;
  if (name == "neldermead" || name == "nelder-mead" || name == "nelder_mead") return Method::neldermead;
  throw InvalidArgument(fmt::format("unknown method \"{}\" (use \"slsqp\", \"lbfgs\", \"cobyla\", \"bobyqa\" or \"neldermead\")", name));
}

std::string method_name(Method m) {
  switch (m) {
    case Method::slsqp: return "slsqp";
    case Method::cobyla: return "cobyla";
    case Method::bobyqa: return "bobyqa";
    case Method::neldermead: return "neldermead";
    case Method::lbfgs: return "lbfgs";
  }
  return "?";
}

void validate_parameters(const std::vector<Parameter>& params) {
  if (params.empty()) throw InvalidArgument("no parameters to calibrate (give at least one {name, lower, upper, start})");
  for (std::size_t i = 0; i < params.size(); ++i) {
    const Parameter& p = params[i];
    const std::string who = p.name.empty() ? fmt::format("parameter {}", i + 1) : fmt::format("parameter '{}'", p.name);
    if (p.name.empty()) throw InvalidArgument(fmt::format("{}: needs a name", who));
    for (std::size_t j = 0; j < i; ++j)
      if (params[j].name == p.name) throw InvalidArgument(fmt::format("{}: name used twice", who));
    if (!std::isfinite(p.lower) || !std::isfinite(p.upper) || !(p.lower < p.upper))
      throw InvalidArgument(fmt::format("{}: need finite lower < upper, got [{}, {}]", who, p.lower, p.upper));
    if (!std::isfinite(p.start) || p.start < p.lower || p.start > p.upper)
      throw InvalidArgument(fmt::format("{}: start {} is outside its bounds [{}, {}]", who, p.start, p.lower, p.upper));
  }
}

namespace {

nlopt::algorithm to_nlopt(Method m) {
  switch (m) {
    case Method::slsqp: return nlopt::LD_SLSQP;
    case Method::cobyla: return nlopt::LN_COBYLA;
    case Method::bobyqa: return nlopt::LN_BOBYQA;
    case Method::neldermead: return nlopt::LN_NELDERMEAD;
    case Method::lbfgs: return nlopt::LD_LBFGS;
  }
  return nlopt::LD_SLSQP;
}

std::string result_name(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "stopval_reached";
    case nlopt::FTOL_REACHED: return "ftol_reached";
    case nlopt::XTOL_REACHED: return "xtol_reached";
    case nlopt::MAXEVAL_REACHED: return "maxeval_reached";
    case nlopt::MAXTIME_REACHED: return "maxtime_reached";
    default: return fmt::format("nlopt_result_{}", static_cast<int>(r));
  }
}

/// Raised inside the NLopt callback when the evaluation budget is spent (not an error).
struct BudgetSpent {};

/// State of one start: maps scaled u ∈ [0,1]^k to θ, evaluates, records, keeps the best point
/// and the first exception thrown by the objective (nlopt.hpp would lose its message).
struct Run {
  const std::vector<Parameter>& params;
  const Objective& f;
  const OptimizerOptions& opt;
  std::vector<HistoryEntry>& history;
  int start_index = 0;
  int evaluations = 0;
  bool budget_spent = false;
  std::exception_ptr error;
  Eigen::VectorXd best_theta;
  Evaluation best{std::numeric_limits<double>::infinity(), {}};
  nlopt::opt* solver = nullptr;

  Eigen::VectorXd theta_of(const double* u) const {
    Eigen::VectorXd t(static_cast<Eigen::Index>(params.size()));
    for (std::size_t i = 0; i < params.size(); ++i) {
      const double ui = std::min(1.0, std::max(0.0, u[i]));  // NLopt may step a hair outside
      t[static_cast<Eigen::Index>(i)] = params[i].lower + ui * (params[i].upper - params[i].lower);
    }
    return t;
  }

  /// One recorded evaluation at u: the value, and with `grad` the gradient in scaled units too
  /// (from OptimizerOptions::gradient; the value comes from the same call).
  double eval(const double* u, bool probe, double* grad = nullptr) {
    if (evaluations >= opt.maxeval) {
      budget_spent = true;
      throw BudgetSpent{};
    }
    Eigen::VectorXd theta = theta_of(u);
    Evaluation e;
    if (grad) {
      e = analytic_gradient(theta, grad);
    } else {
      e = f(theta);
    }
    ++evaluations;
    if (!std::isfinite(e.value)) {
      std::string t;
      for (std::size_t i = 0; i < params.size(); ++i)
        t += fmt::format("{}{} = {}", i ? ", " : "", params[i].name, theta[static_cast<Eigen::Index>(i)]);
      throw InvalidArgument(fmt::format("the objective returned {} at {} (it must return a finite number)", e.value, t));
    }
    history.push_back({theta, e.value, e.parts, start_index, probe});
    if (opt.observer) opt.observer(history.back());
    if (e.value < best.value) {
      best = e;
      best_theta = theta;
    }
    return e.value;
  }

  /// OptimizerOptions::gradient at θ, in scaled units into grad; returns its evaluation.
  Evaluation analytic_gradient(const Eigen::VectorXd& theta, double* grad) const {
    Eigen::VectorXd g;
    Evaluation e = opt.gradient(theta, g);
    if (g.size() != theta.size() || !g.allFinite())
      throw InvalidArgument(fmt::format("the objective's gradient has {} values (finite: {}) for {} parameters", g.size(), g.allFinite(),
                                        theta.size()));
    for (std::size_t i = 0; i < params.size(); ++i) grad[i] = g[static_cast<Eigen::Index>(i)] * (params[i].upper - params[i].lower);
    return e;
  }

  /// The gradient at u (scaled units) whose value f0 is known: the analytic one (not counted as
  /// an evaluation: the value was), or central differences with probes (one-sided where a
  /// central probe would leave [0, 1]).
  void gradient_at(const std::vector<double>& u, double f0, std::vector<double>& grad) {
    if (opt.gradient) {
      analytic_gradient(theta_of(u.data()), grad.data());
      return;
    }
    const double h = opt.fd_step;
    std::vector<double> w(u);
    for (std::size_t i = 0; i < u.size(); ++i) {
      const double ui = std::min(1.0, std::max(0.0, u[i]));
      const double up = ui + h <= 1.0 ? ui + h : ui, dn = ui - h >= 0.0 ? ui - h : ui;
      double fp = f0, fm = f0;
      if (up != ui) {
        w[i] = up;
        fp = eval(w.data(), true);
      }
      if (dn != ui) {
        w[i] = dn;
        fm = eval(w.data(), true);
      }
      w[i] = u[i];
      grad[i] = (fp - fm) / (up - dn);
    }
  }

  // Deferred gradients (OptimizerOptions::defer_gradient). NLopt's SLSQP (slsqp.c, unchanged since
  // 2010) asks for a gradient in three places: at the start; at the first trial x = x0 + s of
  // each line search ("mode -2"), where it keeps the gradient when the trial passes the
  // sufficient-decrease test f(x) − f(x0) <= 0.1 ∇f(x0)·s (bounds only: no constraint terms) and
  // else discards it, trying smaller steps with values only; and at the point a line search
  // accepted after such value-only trials ("mode -1"). So a gradient request right after another
  // one is a first trial, x0 being the previous request's point; after a value-only call it is
  // an accepted point (always computed).
  enum class Call { none, value, gradient, deferred };
  Call last = Call::none;
  std::vector<double> x0{}, g0{};  // the last gradient request's point and gradient (defaults: no slot in the aggregate init)
  double f0 = 0.0;
  int deferred = 0;
  bool deferral_failed = false;

  /// Whether NLopt's line search will reject the first trial u with value fu: the test above with
  /// a margin far above the rounding of x0 + s (s is NLopt's, u − x0 ours), so that a borderline
  /// trial gets its gradient.
  bool surely_rejected(const std::vector<double>& u, double fu) const {
    double gs = 0.0, mag = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      gs += g0[i] * (u[i] - x0[i]);
      mag += std::abs(g0[i]) * (std::abs(u[i]) + std::abs(x0[i]));
    }
    const double margin = 1e-9 * (mag + std::abs(f0) + std::abs(fu));
    return fu - f0 > 0.1 * gs + margin;
  }

  /// NLopt callback: value at u and, when asked, the gradient in scaled units.
  double operator()(const std::vector<double>& u, std::vector<double>& grad) {
    if (error || budget_spent) return HUGE_VAL;
    try {
      if (grad.empty()) {
        last = Call::value;
        return eval(u.data(), false);
      }
      if (last == Call::deferred && !deferral_failed) {
        // NLopt used a step predicted to be rejected (a different NLopt?): it read the previous
        // point's gradient for this one. Stop deferring for this start and say so.
        deferral_failed = true;
        failure_note = "a line-search step predicted to be rejected was accepted; gradients are no longer deferred in this start";
      }
      const bool first_trial = defer && !deferral_failed && last == Call::gradient;
      double v;
      if (first_trial || !opt.gradient) {
        v = eval(u.data(), false);
        if (first_trial && surely_rejected(u, v)) {
          std::copy(g0.begin(), g0.end(), grad.begin());  // never read: NLopt rejects this step
          last = Call::deferred;
          ++deferred;
          return v;
        }
        gradient_at(u, v, grad);
      } else {
        v = eval(u.data(), false, grad.data());
      }
      last = Call::gradient;
      x0 = u;
      g0 = grad;
      f0 = v;
      return v;
    } catch (const BudgetSpent&) {
    } catch (const std::exception&) {
      error = std::current_exception();
    }
    solver->force_stop();
    return HUGE_VAL;
  }
  bool defer = false;
  std::string failure_note{};  // set when a deferral went wrong (above)
};

double trampoline(const std::vector<double>& u, std::vector<double>& grad, void* data) {
  return (*static_cast<Run*>(data))(u, grad);
}

/// Which stopping criterion a start ended on, or which it missed and by how much: the
/// last two points the optimiser asked for (not probes) give the relative step in scaled units and
/// the objective change that xtol_rel and ftol_abs are compared with.
std::string stop_criterion(const std::string& status, const OptimizerOptions& opt, const std::vector<Parameter>& params,
                           const std::vector<HistoryEntry>& history, int index) {
  if (status == "xtol_reached") return fmt::format("xtol_rel {:g} reached", opt.xtol_rel);
  if (status == "ftol_reached") return fmt::format("ftol_abs {:g} reached", opt.ftol_abs);
  if (status == "success" || status == "stopval_reached") return "NLopt's own test (" + status + ")";
  if (status == "roundoff_limited") return "round-off: no smaller step lowers the objective (the best point is kept)";
  const HistoryEntry *last = nullptr, *before = nullptr;
  for (auto it = history.rbegin(); it != history.rend() && !before; ++it) {
    if (it->start != index || it->probe) continue;
    if (!last) last = &*it;
    else if (it->theta != last->theta) before = &*it;  // the previous distinct point
  }
  std::string moved;
  if (last && before) {
    double dx = 0.0, x = 0.0;
    for (std::size_t i = 0; i < params.size(); ++i) {
      const double w = params[i].upper - params[i].lower;
      const auto j = static_cast<Eigen::Index>(i);
      dx = std::max(dx, std::abs(last->theta[j] - before->theta[j]) / w);
      x = std::max(x, std::abs(last->theta[j] - params[i].lower) / w);
    }
    moved = fmt::format("; the last step moved the parameters by {:.2g} (relative) and the objective by {:.2g}", x > 0 ? dx / x : dx,
                        std::abs(last->value - before->value));
  }
  if (status == "maxeval_reached")
    return fmt::format("missed: maxeval {} spent before xtol_rel {:g} or ftol_abs {:g}{}", opt.maxeval, opt.xtol_rel, opt.ftol_abs, moved);
  return fmt::format("missed: stopped by {} before xtol_rel {:g} or ftol_abs {:g}{}", status, opt.xtol_rel, opt.ftol_abs, moved);
}

StartResult run_start(const std::vector<Parameter>& params, const Objective& f, const OptimizerOptions& opt,
                      const Eigen::VectorXd& u0, int index, std::vector<HistoryEntry>& history,
                      std::vector<std::string>& warnings) {
  const unsigned k = static_cast<unsigned>(params.size());
  Method method = opt.method;
  if (method == Method::bobyqa && k < 2) {
    // NLopt's BOBYQA needs at least 2 variables (Powell's original restriction).
    warnings.push_back("bobyqa needs at least 2 parameters; used cobyla for this 1-parameter problem");
    method = Method::cobyla;
  }
  nlopt::opt solver(to_nlopt(method), k);
  solver.set_lower_bounds(std::vector<double>(k, 0.0));
  solver.set_upper_bounds(std::vector<double>(k, 1.0));
  solver.set_xtol_rel(opt.xtol_rel);
  solver.set_ftol_abs(opt.ftol_abs);
  solver.set_maxeval(opt.maxeval);  // our own budget (Run::eval) also counts the gradient probes
  if (!uses_gradient(method)) solver.set_initial_step(opt.initial_step);
  Run run{params, f, opt, history, index, 0, false, nullptr, Eigen::VectorXd(), {HUGE_VAL, {}}, &solver};
  run.defer = opt.defer_gradient && method == Method::slsqp;
  solver.set_min_objective(&trampoline, &run);

  std::vector<double> u(u0.data(), u0.data() + u0.size());
  double fmin = HUGE_VAL;
  StartResult out;
  out.start = run.theta_of(u0.data());
  try {
    const nlopt::result r = solver.optimize(u, fmin);
    out.status = result_name(r);
    out.converged = r == nlopt::SUCCESS || r == nlopt::FTOL_REACHED || r == nlopt::XTOL_REACHED || r == nlopt::STOPVAL_REACHED;
  } catch (const nlopt::roundoff_limited&) {
    // Usual for SLSQP near an optimum with finite-difference gradients: keep the best point.
    out.status = "roundoff_limited";
    out.converged = true;
    warnings.push_back(fmt::format("start {}: NLopt stopped on round-off (roundoff_limited); the best point seen is kept", index + 1));
  } catch (const nlopt::forced_stop&) {
    out.status = "forced_stop";
  } catch (const std::exception& e) {
    if (!run.error) {
      out.status = std::string("nlopt error: ") + e.what();
      warnings.push_back(fmt::format("start {}: {}", index + 1, out.status));
    }
  }
  if (run.error) std::rethrow_exception(run.error);
  if (run.budget_spent) {
    out.status = "maxeval_reached";
    out.converged = false;
  }
  out.criterion = stop_criterion(out.status, opt, params, history, index);
  if (out.status == "maxeval_reached")
    warnings.push_back(fmt::format("start {}: evaluation budget of {} spent before convergence (raise maxeval): {}", index + 1, opt.maxeval,
                                   out.criterion));
  if (run.evaluations == 0) throw Error(fmt::format("start {}: NLopt made no evaluation ({})", index + 1, out.status));
  if (!run.failure_note.empty()) warnings.push_back(fmt::format("start {}: {}", index + 1, run.failure_note));
  out.theta = run.best_theta;
  out.value = run.best.value;
  out.evaluations = run.evaluations;
  out.deferred_gradients = run.deferred;
  return out;
}

}  // namespace

Eigen::VectorXd central_gradient(const Objective& f, const Eigen::VectorXd& theta, const Eigen::VectorXd& h) {
  if (h.size() != theta.size()) throw DimensionMismatch(fmt::format("gradient: {} steps for {} parameters", h.size(), theta.size()));
  Eigen::VectorXd g(theta.size());
  for (Eigen::Index i = 0; i < theta.size(); ++i) {
    Eigen::VectorXd tp = theta, tm = theta;
    tp[i] += h[i];
    tm[i] -= h[i];
    g[i] = (f(tp).value - f(tm).value) / (2.0 * h[i]);
  }
  return g;
}

namespace {

void validate_options(const OptimizerOptions& opt) {
  if (opt.multistart < 1) throw InvalidArgument(fmt::format("multistart must be >= 1, got {}", opt.multistart));
  if (opt.maxeval < 1) throw InvalidArgument(fmt::format("maxeval must be >= 1, got {}", opt.maxeval));
  if (!(opt.fd_step > 0.0 && opt.fd_step <= kMaxFdStep))
    throw InvalidArgument(fmt::format("fd_step must be in (0, {}] (scaled units), got {}", kMaxFdStep, opt.fd_step));
  if (!(opt.xtol_rel >= 0.0) || !(opt.ftol_abs >= 0.0)) throw InvalidArgument("xtol_rel and ftol_abs must be >= 0");
  if (opt.hops < 0) throw InvalidArgument(fmt::format("hops must be >= 0, got {}", opt.hops));
  if (!(opt.hop_step > 0.0 && opt.hop_step <= 1.0))
    throw InvalidArgument(fmt::format("hop_step must be in (0, 1] (scaled units: a fraction of each range), got {}", opt.hop_step));
}

/// The starts in scaled units [0, 1]^k: the given start first, then uniform draws in order from
/// one stream (the same points whatever start_threads is).
std::vector<Eigen::VectorXd> draw_starts(const std::vector<Parameter>& params, const OptimizerOptions& opt) {
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  Rng rng(opt.seed, hash_label("multistart"));
  std::vector<Eigen::VectorXd> u0s;
  for (int s = 0; s < opt.multistart; ++s) {
    Eigen::VectorXd u0(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const Parameter& p = params[static_cast<std::size_t>(i)];
      u0[i] = s == 0 ? (p.start - p.lower) / (p.upper - p.lower) : rng.uniform01();
    }
    u0s.push_back(std::move(u0));
  }
  return u0s;
}

/// One start's outcome. Each start keeps its own history and warnings, merged in start order
/// afterwards, so the result is the same whether the starts run one after another or side by side.
struct StartRun {
  StartResult sr;
  std::vector<HistoryEntry> history;
  std::vector<std::string> warnings;
  int prepare_evaluations = 0;
};

/// θ in scaled units [0, 1]^k (clamped: a point on a bound stays on it).
Eigen::VectorXd scaled_point(const std::vector<Parameter>& params, const Eigen::VectorXd& theta) {
  Eigen::VectorXd u(theta.size());
  for (Eigen::Index i = 0; i < theta.size(); ++i) {
    const Parameter& p = params[static_cast<std::size_t>(i)];
    u[i] = std::clamp((theta[i] - p.lower) / (p.upper - p.lower), 0.0, 1.0);
  }
  return u;
}

/// Monotone basin hopping from start s's optimum: opt.hops jumps of up to ±hop_step (scaled) per
/// parameter from the best point so far, each followed by a local run; a lower optimum replaces
/// the start's (its status and convergence with it). One random stream per start, so the hops
/// do not depend on start_threads.
void hop_basins(const std::vector<Parameter>& params, const Objective& f, const OptimizerOptions& opt, int s, StartRun& out) {
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  Rng rng(opt.seed, hash_label("hops") + static_cast<std::uint64_t>(s));
  // A hop only has to tell which basin it fell into: its local run stops at a looser tolerance
  // (most of a local run's evaluations go into its last digits), and the best point is polished
  // at the caller's tolerances once, after the last hop.
  OptimizerOptions loose = opt;
  loose.xtol_rel = std::max(opt.xtol_rel, 1e-3);
  loose.ftol_abs = std::max(opt.ftol_abs, 1e-5);
  bool moved = false;
  for (int h = 0; h < opt.hops; ++h) {
    Eigen::VectorXd u = scaled_point(params, out.sr.theta);
    for (Eigen::Index i = 0; i < k; ++i) u[i] = std::clamp(u[i] + opt.hop_step * (2.0 * rng.uniform01() - 1.0), 0.0, 1.0);
    const StartResult hop = run_start(params, f, loose, u, s, out.history, out.warnings);
    out.sr.evaluations += hop.evaluations;
    ++out.sr.hops;
    if (hop.value < out.sr.value - opt.ftol_abs) {
      ++out.sr.hops_improved;
      out.sr.theta = hop.theta;
      out.sr.value = hop.value;
      moved = true;
    }
  }
  if (!moved) return;
  const StartResult polish = run_start(params, f, opt, scaled_point(params, out.sr.theta), s, out.history, out.warnings);
  out.sr.evaluations += polish.evaluations;
  out.sr.status = polish.status;
  out.sr.criterion = polish.criterion;
  out.sr.converged = polish.converged;
  if (polish.value < out.sr.value) {
    out.sr.theta = polish.theta;
    out.sr.value = polish.value;
  }
}

/// Start s from the scaled point u0: moved first by opt.prepare_start when there is one (its
/// point clamped into the box), then optimised by run_start.
void run_one_start(const std::vector<Parameter>& params, const Objective& f, const OptimizerOptions& opt, Eigen::VectorXd u0, int s,
                   StartRun& out) {
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  Eigen::VectorXd given(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Parameter& p = params[static_cast<std::size_t>(i)];
    given[i] = p.lower + u0[i] * (p.upper - p.lower);
  }
  PreparedStart ps;
  if (opt.prepare_start) {
    ps = opt.prepare_start(given);
    out.prepare_evaluations = ps.evaluations;
    if (!ps.note.empty()) out.warnings.push_back(fmt::format("start {}: {}", s + 1, ps.note));
    u0 = scaled_point(params, ps.theta);
  }
  out.sr = run_start(params, f, opt, u0, s, out.history, out.warnings);
  if (opt.hops > 0) hop_basins(params, f, opt, s, out);
  out.sr.given = given;
  out.sr.start_status = ps.status;
  out.sr.start_criterion_before = ps.criterion_before;
  out.sr.start_criterion_after = ps.criterion_after;
}

/// The starts' runs into res in start order: counts, history and warnings appended, the best
/// start's point, value and status (the first on ties), and the objective's parts at that point.
void merge_starts(std::vector<StartRun>& runs, OptimizationResult& res) {
  for (std::size_t s = 0; s < runs.size(); ++s) {
    StartRun& r = runs[s];
    res.start_evaluations += r.prepare_evaluations;
    res.history.insert(res.history.end(), std::make_move_iterator(r.history.begin()), std::make_move_iterator(r.history.end()));
    res.warnings.insert(res.warnings.end(), r.warnings.begin(), r.warnings.end());
    res.evaluations += r.sr.evaluations;
    if (s == 0 || r.sr.value < res.value) {
      res.best = static_cast<int>(s);
      res.theta = r.sr.theta;
      res.value = r.sr.value;
      res.status = r.sr.status;
      res.converged = r.sr.converged;
    }
    res.starts.push_back(std::move(r.sr));
  }
  for (const HistoryEntry& h : res.history)
    if (h.value == res.value && h.theta == res.theta) {
      res.parts = h.parts;
      break;
    }
}

/// Names (and warns of) the parameters whose optimum sits within 1e-6 of its range of a bound.
void flag_parameters_at_bounds(const std::vector<Parameter>& params, OptimizationResult& res) {
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(params.size()); ++i) {
    const Parameter& p = params[static_cast<std::size_t>(i)];
    const double tol = 1e-6 * (p.upper - p.lower);
    if (res.theta[i] - p.lower <= tol || p.upper - res.theta[i] <= tol) {
      res.at_bounds.push_back(p.name);
      res.warnings.push_back(fmt::format("parameter '{}' = {} sits at a bound of [{}, {}]: widen the range if physically allowed",
                                         p.name, res.theta[i], p.lower, p.upper));
    }
  }
}

/// Distinct optima: the starts, best first, clustered by objective and by scaled distance (one
/// index per cluster in res.optima); warns when the starts did not all reach one optimum.
void cluster_optima(const std::vector<Parameter>& params, const OptimizerOptions& opt, OptimizationResult& res) {
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  std::vector<int> order(res.starts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return res.starts[static_cast<std::size_t>(a)].value < res.starts[static_cast<std::size_t>(b)].value; });
  for (int s : order) {
    const StartResult& a = res.starts[static_cast<std::size_t>(s)];
    bool known = false;
    for (int o : res.optima) {
      const StartResult& b = res.starts[static_cast<std::size_t>(o)];
      known = known || (std::abs(a.value - b.value) <= 1e-6 + 1e-4 * std::abs(b.value) && (scaled_point(params, a.theta) - scaled_point(params, b.theta)).norm() <= 1e-2 * std::sqrt(static_cast<double>(k)));
    }
    if (!known) res.optima.push_back(s);
  }
  res.starts_agree = res.optima.size() == 1;
  if (!res.starts_agree) {
    int agree = 0;
    for (const StartResult& s : res.starts) agree += std::abs(s.value - res.value) <= 1e-6 + 1e-4 * std::abs(res.value);
    res.warnings.push_back(fmt::format("the {} starts ended at {} distinct optima ({} of them at the best objective {}): the problem is "
                                       "multimodal or flat along some direction; see optima and identifiability.directions",
                                       opt.multistart, res.optima.size(), agree, res.value));
  }
}

}  // namespace

OptimizationResult minimize(const std::vector<Parameter>& params, const Objective& f, const OptimizerOptions& opt) {
  validate_parameters(params);
  validate_options(opt);
  const std::vector<Eigen::VectorXd> u0s = draw_starts(params, opt);
  std::vector<StartRun> runs(static_cast<std::size_t>(opt.multistart));
  auto run_one = [&](int s) { run_one_start(params, f, opt, u0s[static_cast<std::size_t>(s)], s, runs[static_cast<std::size_t>(s)]); };
  if (opt.start_threads > 1 && opt.multistart > 1) {
    // One task per start; a start's exception reaches this thread (the pool rethrows it).
    pool::parallel_for(opt.multistart, std::min(opt.start_threads, opt.multistart),
                       [&](long s) { run_one(static_cast<int>(s)); });
  } else {
    for (int s = 0; s < opt.multistart; ++s) run_one(s);
  }
  OptimizationResult res;
  merge_starts(runs, res);
  flag_parameters_at_bounds(params, res);
  cluster_optima(params, opt, res);
  return res;
}

}  // namespace smi::improve
