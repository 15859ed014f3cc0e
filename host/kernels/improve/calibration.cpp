// SPDX-License-Identifier: MIT
#include "kernels/improve/calibration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <tuple>

#include "kernels/improve/calibration_progress.hpp"
#include "kernels/improve/overlap_start.hpp"
#include "platform/core/errors.hpp"

namespace smi::improve {

namespace {

/// The penalty and prior terms, added to the metric: each is reported as one more part
/// ("penalty", then "prior"), so histories and results show how much of the optimum is prior
/// knowledge and how much is fit.
struct Extras {
  ThetaFunction pen;
  std::vector<PriorTerm> priors;
  double weight = 1.0;

  Extras(const CalibrationProblem& p, const CalibrationOptions& o) : pen(p.penalty), priors(p.priors), weight(o.prior_weight) {}
  bool any() const { return pen || !priors.empty(); }
  double penalty(const Eigen::VectorXd& t) const {
    const double v = pen(t);
    if (!std::isfinite(v)) throw InvalidArgument(fmt::format("penalty returned {} (it must be a finite number)", v));
    return v;
  }
  double prior(const Eigen::VectorXd& t) const { return prior_sum(priors, weight, t); }
  void add(Evaluation& e, const Eigen::VectorXd& t) const {
    if (!any()) return;
    if (e.parts.size() == 0) e.parts = Eigen::VectorXd::Constant(1, e.value);  // a metric without parts
    auto push = [&e](double v) {
      e.value += v;
      e.parts.conservativeResize(e.parts.size() + 1);
      e.parts[e.parts.size() - 1] = v;
    };
    if (pen) push(penalty(t));
    if (!priors.empty()) push(prior(t));
  }
  double total(const Eigen::VectorXd& t) const { return (pen ? penalty(t) : 0.0) + (priors.empty() ? 0.0 : prior(t)); }
};

Objective with_extras(const Extras& x, Objective metric) {
  if (!x.any()) return metric;
  return [metric = std::move(metric), x](const Eigen::VectorXd& t) {
    Evaluation e = metric(t);
    x.add(e, t);
    return e;
  };
}

/// The metric's gradient (analytic, or by model differences) plus the extras' gradient by central
/// differences (functions of θ only: no model run), steps 1e-7 of each range, one-sided at a bound.
ObjectiveGradient gradient_with_extras(const Extras& x, const std::vector<Parameter>& params, const StatisticalObjective& obj) {
  return [&obj, x, params](const Eigen::VectorXd& t, Eigen::VectorXd& g) {
    Evaluation e = obj.value_and_gradient(t, g);
    x.add(e, t);
    if (x.any())
      for (Eigen::Index i = 0; i < t.size(); ++i) {
        const Parameter& p = params[static_cast<std::size_t>(i)];
        const double h = 1e-7 * (p.upper - p.lower);
        Eigen::VectorXd up = t, dn = t;
        up[i] = std::min(p.upper, t[i] + h);
        dn[i] = std::max(p.lower, t[i] - h);
        g[i] += (x.total(up) - x.total(dn)) / (up[i] - dn[i]);
      }
    return e;
  };
}

/// Labels of the parts: the metric's own (responses), or one "metric"/"objective" part when it
/// gave none, then "penalty" and "prior" when present.
std::vector<std::string> part_labels(const Extras& x, std::vector<std::string> own, Eigen::Index parts, const char* whole) {
  const Eigen::Index extras = (x.pen ? 1 : 0) + (x.priors.empty() ? 0 : 1);
  if (extras == 0) return own;
  if (parts != static_cast<Eigen::Index>(own.size()) + extras) own = {whole};
  if (x.pen) own.push_back("penalty");
  if (!x.priors.empty()) own.push_back("prior");
  return own;
}

/// Wires the gradient (model Jacobian, model differences, or none: objective differences) into
/// the statistical objective according to o.gradient; says which in out.gradient.
void choose_gradient(const CalibrationProblem& p, const CalibrationOptions& o, StatisticalObjective& obj) {
  if (o.gradient != "auto" && o.gradient != "analytic" && o.gradient != "model" && o.gradient != "differences")
    throw InvalidArgument(fmt::format("gradient must be \"auto\", \"analytic\", \"model\" or \"differences\", got \"{}\"", o.gradient));
  if (o.model_differences != "forward" && o.model_differences != "central")
    throw InvalidArgument(fmt::format("model_differences must be \"forward\" or \"central\", got \"{}\"", o.model_differences));
  if (o.gradient == "differences") return;
  if (p.jacobian && o.gradient != "model") obj.set_model_jacobian(p.jacobian);
  if (!obj.has_model_jacobian() && o.gradient != "analytic") obj.set_model_differences(o.model_differences == "central", o.model_step);
  if (o.gradient == "analytic" && !obj.has_gradient())
    throw InvalidArgument("gradient = \"analytic\" needs metric \"pr\" or \"loglik\", a bandwidth rule with a derivative (silverman, "
                          "normal, 1.06, scott, robust, mad; not lscv or sj) and a model with a gradient (an smi.kriging, or an object with m:gradient(X)); use gradient = \"auto\"");
  if (o.gradient == "model" && !obj.has_gradient())
    throw InvalidArgument("gradient = \"model\" needs metric \"pr\" or \"loglik\" and a bandwidth rule with a derivative (silverman, normal, "
                          "1.06, scott, robust, mad; not lscv or sj); use gradient = \"auto\" or \"differences\"");
}

/// The objective form: the caller's objective (plus penalty and prior) minimised.
Objective minimize_objective(const CalibrationProblem& p, const Extras& x, const OptimizerOptions& oo, CalibrationOutcome& out) {
  Objective f = with_extras(x, p.objective);
  OptimizerOptions od = oo;
  od.defer_gradient = true;  // the objective's differences: 2k evaluations a gradient
  out.opt = minimize(p.params, f, od);
  out.part_names = part_labels(x, p.objective_parts ? p.objective_parts() : std::vector<std::string>{}, out.opt.parts.size(), "objective");
  return f;
}

/// Whether several evaluations may run at once on the thread pool: a native model or one that
/// takes turns itself (model_thread_safe), and no Lua metric, penalty, progress or prior.
bool thread_safe(const CalibrationProblem& p) {
  const bool callbacks_free = p.callbacks_thread_safe ||
                              (!p.metric && !p.penalty && !p.progress && std::none_of(p.priors.begin(), p.priors.end(), [](const PriorTerm& t) { return bool(t.fn); }));
  return (p.native_model || p.model_thread_safe) && callbacks_free;
}

/// The statistical form: builds the CRN objective in out.stat, chooses threads, gradient and
/// start preparation, and minimises it. oo receives the gradient, which the profile intervals reuse.
Objective minimize_statistical(const CalibrationProblem& p, const CalibrationOptions& o, const Extras& x, OptimizerOptions& oo,
                               CalibrationOutcome& out) {
  std::vector<std::string> responses;
  for (const auto& r : p.responses) responses.push_back(r.name);
  // A native model (or a Lua model that takes turns); then, when nothing else in an evaluation
  // calls Lua, the starts run side by side on `threads` threads (the same result as one after
  // another), each evaluation on one.
  StatisticalOptions so = p.stat;
  const int start_threads = std::min(p.stat.threads, o.optimizer.multistart);
  const bool side_by_side = thread_safe(p) && start_threads > 1;
  const Model model = p.native_model ? p.native_model(side_by_side ? 1 : 2) : p.model;
  if (!model) throw InvalidArgument("the calibration has neither an objective nor a model");
  if (side_by_side) {
    oo.start_threads = start_threads;
    so.threads = 1;
  }
  out.stat.emplace(p.inputs, p.responses, p.params, model, so, p.metric);
  StatisticalObjective& obj = *out.stat;
  choose_gradient(p, o, obj);
  Objective f = with_extras(x, [&obj](const Eigen::VectorXd& t) { return obj(t); });
  if (obj.has_gradient()) {
    oo.gradient = gradient_with_extras(x, p.params, obj);
    out.gradient = obj.has_model_jacobian() ? "analytic" : "model_differences";
  }
  // A gradient by differences (k model passes, or 2k objective evaluations) costs far more than
  // a value: compute it only where SLSQP uses it (OptimizerOptions::defer_gradient).
  oo.defer_gradient = !obj.has_model_jacobian();
  if (o.moment_start)
    oo.prepare_start = [&obj](const Eigen::VectorXd& t) { return moment_start(obj, t); };
  else if (o.overlap_start)
    oo.prepare_start = [&obj](const Eigen::VectorXd& t) { return overlap_start(obj, t); };
  out.opt = minimize(p.params, f, oo);
  // per-response parts, or one "metric" part when a custom metric returned a bare number
  out.part_names = part_labels(x, responses, out.opt.parts.size(), "metric");
  return f;
}

void append(std::vector<std::string>& to, const std::vector<std::string>& from) { to.insert(to.end(), from.begin(), from.end()); }

/// Identifiability at the optimum (the Hessian's spans), and when asked the directions that fit
/// as well as the optimum (with the predicted responses' summaries in the statistical form).
void add_identifiability(const CalibrationProblem& p, const CalibrationOptions& o, const Objective& f_plain, CalibrationOutcome& out) {
  // The near-optimal analysis's own line: its evaluations against a rough budget (a sweep of
  // every parameter, then every direction's profile).
  const long k = static_cast<long>(p.params.size());
  std::shared_ptr<ProgressTracker> line;
  if (p.progress_line)
    line = std::make_shared<ProgressTracker>(p.progress_line, "near-optimal", static_cast<int>(k * (o.ident.points + o.directions.points) + 2 * k * k), 0);
  const Objective f = line ? Objective([f_plain, line](const Eigen::VectorXd& t) {
    Evaluation e = f_plain(t);
    line->count();
    return e;
  })
                           : f_plain;
  struct Finish {
    std::shared_ptr<ProgressTracker> l;
    ~Finish() {
      if (l) l->finish();
    }
  } finish{line};
  out.ident = identifiability(p.params, f, out.opt.theta, o.ident);
  append(out.warnings, out.ident->warnings);
  if (!o.identifiability_directions) return;
  DirectionsOptions d = o.directions;
  d.tolerance = out.tolerance;
  Summaries summ;
  if (out.stat) summ = [&obj = *out.stat](const Eigen::VectorXd& t) { return obj.summaries(t); };
  out.directions = identifiability_directions(p.params, f, out.opt.theta, out.opt.value, d, summ);
  append(out.warnings, out.directions->warnings);
}

/// With several starts: whether they reached the best's optimum where the data can tell (within
/// the tolerance, no barrier above it between them; start_agreement.hpp). The starts' optima
/// that fit as well join the near-optimal set: they are calibrations the data cannot reject.
void add_start_agreement(const CalibrationProblem& p, const Objective& f, CalibrationOutcome& out) {
  out.agreement = start_agreement(p.params, f, out.opt, out.tolerance, out.stat ? prediction_check(*out.stat) : PredictionCheck{});
  if (!out.opt.starts_agree) out.warnings.push_back(describe(*out.agreement));
  if (!out.directions) return;
  for (std::size_t i = 0; i < out.opt.starts.size(); ++i) {
    const StartResult& st = out.opt.starts[i];
    if (!out.agreement->rows[i].within || static_cast<int>(i) == out.opt.best) continue;
    out.directions->near_optimal.push_back(st.theta);
    out.directions->near_optimal_values.push_back(st.value);
  }
}

/// Warns when the calibrated inputs' samples leave the surrogates' design bounds.
void add_design_bound_warnings(const CalibrationOptions& o, const StatisticalObjective& obj, CalibrationOutcome& out) {
  std::vector<std::string> names;
  std::vector<double> means;
  const auto m = obj.input_moments(out.opt.theta);
  for (std::size_t j = 0; j < obj.inputs().size(); ++j) {
    names.push_back(obj.inputs()[j].name);
    means.push_back(m[j].first);
  }
  append(out.warnings, design_bound_warnings(names, obj.inputs_at(out.opt.theta), means, o.design));
}

/// PR with the data points at hand: the tolerance measured from them (pr_tolerance.hpp) replaces
/// the unit-free default, which is ten times tighter than nine specimens can tell.
void add_measured_tolerance(const CalibrationProblem& p, const CalibrationOptions& o, CalibrationOutcome& out) {
  const StatisticalObjective& obj = *out.stat;
  const PrTolerance t = measure_pr_tolerance(obj, out.opt.theta, o.tolerance_resamples, p.stat.seed, p.stat.threads);
  std::string names;
  for (const ResponseSpec& r : obj.responses()) names += (names.empty() ? "" : ", ") + r.name;
  out.tolerance = t.value;
  out.tolerance_basis = fmt::format("standard deviation of the summed PR of {} at the optimum over {} bootstrap resamples of the {} data {}{}",
                                    names, t.resamples, obj.responses().front().data.size(), t.paired ? "rows" : "points per response",
                                    t.failed > 0 ? fmt::format(" ({} degenerate resamples left out)", t.failed) : "");
}

/// Bootstrap of the statistical calibration: each replicate recalibrates an objective on
/// resampled data, built the same way as the original (gradient, start preparation, extras).
void add_bootstrap(const CalibrationProblem& p, const CalibrationOptions& o, const Extras& x, const StatisticalObjective& obj,
                   CalibrationOutcome& out) {
  std::vector<Eigen::VectorXd> data;
  for (const auto& r : obj.responses()) data.push_back(r.data);
  BootstrapOptions bo = *o.bootstrap;
  if (thread_safe(p)) bo.threads = p.stat.threads;  // replicates side by side, the same numbers
  ReplicateFactory make = [&obj, &o, &p, x, side_by_side = bo.threads > 1](const std::vector<Eigen::VectorXd>& d) {
    auto rep_obj = std::make_shared<StatisticalObjective>(obj.with_data(d));
    if (side_by_side) rep_obj->set_threads(1);
    Replicate rep;
    rep.f = with_extras(x, [rep_obj](const Eigen::VectorXd& t) { return (*rep_obj)(t); });
    if (rep_obj->has_gradient()) rep.gradient = gradient_with_extras(x, p.params, *rep_obj);
    if (o.moment_start)
      rep.prepare_start = [rep_obj](const Eigen::VectorXd& t) { return moment_start(*rep_obj, t); };
    else if (o.overlap_start)
      rep.prepare_start = [rep_obj](const Eigen::VectorXd& t) { return overlap_start(*rep_obj, t); };
    rep.keep = rep_obj;
    return rep;
  };
  if (p.progress_line) {
    auto line = std::make_shared<ProgressTracker>(p.progress_line, "bootstrap", bo.replicates, 0);
    bo.progress = [line](int done, int, long evaluations) { line->unit_done(done, evaluations); };
  }
  out.boot = bootstrap_calibration(p.params, out.opt.theta, data, make, bo);
  append(out.warnings, out.boot->warnings);
}

/// Runs one analysis after the optimum. When it fails (a solver or Lua model that breaks at a
/// profile point, a path point, a resampled data set), the optimum found stands and the failure
/// is a warning naming the analysis and the error: a diagnostic must not lose the result. An
/// interruption or exhausted memory still ends the call.
template <class Analysis>
void after_optimum(CalibrationOutcome& out, const char* what, Analysis&& analysis) {
  try {
    analysis();
  } catch (const smi::Interrupted&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    out.warnings.push_back(fmt::format("{} could not be computed (the optimum above stands): {}", what, e.what()));
    out.not_computed[what] = e.what();
  }
}

}  // namespace

double prior_sum(const std::vector<PriorTerm>& priors, double weight, const Eigen::VectorXd& t) {
  double sum = 0.0;
  for (const PriorTerm& p : priors) {
    const double v = p.param >= 0 ? t[p.param] : p.fn(t);
    if (!std::isfinite(v)) throw InvalidArgument(fmt::format("prior '{}': its function returned {} (it must return a finite number)", p.label, v));
    const double z = (v - p.mean) / p.std;
    sum += 0.5 * z * z;
  }
  return weight * sum;
}

std::pair<double, std::string> near_optimal_tolerance(const CalibrationProblem& p, const CalibrationOptions& o, double optimum) {
  if (o.directions_tolerance > 0.0) return {o.directions_tolerance, "identifiability.tolerance as given"};
  const bool statistical = static_cast<bool>(p.model || p.native_model);
  if (statistical && !p.metric && p.stat.metric == MetricKind::pr)
    return {0.01 * static_cast<double>(p.responses.size()),
            fmt::format("PR is unit-free in [0, 2] per response: 0.01 for each of the {} responses", p.responses.size())};
  if (statistical && !p.metric && p.stat.metric == MetricKind::loglik)
    return {1.920729, "likelihood-ratio bound ½ χ²₁(0.95) = 1.920729 on minus the log-likelihood"};
  return {1e-6 * std::max(1.0, std::abs(optimum)), "1e-6 of the optimum's value (at least 1e-6): the objective's scale is unknown"};
}

CalibrationOutcome calibrate(const CalibrationProblem& p, const CalibrationOptions& o) {
  validate_parameters(p.params);
  CalibrationOutcome out;
  OptimizerOptions oo = o.optimizer;
  const Extras x(p, o);
  std::shared_ptr<ProgressTracker> line;
  if (p.progress_line)
    line = std::make_shared<ProgressTracker>(p.progress_line, "calibration", o.optimizer.multistart,
                                             static_cast<long>(o.optimizer.multistart) * o.optimizer.maxeval * (1 + o.optimizer.hops));
  if (line || p.progress)
    oo.observer = [line, lua = p.progress](const HistoryEntry& h) {
      if (line) line->evaluation(h);
      if (lua) lua(h);
    };
  const bool statistical = static_cast<bool>(p.model || p.native_model);
  if (!statistical && !p.objective) throw InvalidArgument("the calibration has neither an objective nor a model");
  const Objective f = statistical ? minimize_statistical(p, o, x, oo, out) : minimize_objective(p, x, oo, out);
  if (line) line->finish();
  if (!statistical && uses_gradient(o.optimizer.method)) out.gradient = "differences";
  if (statistical && uses_gradient(o.optimizer.method) && out.gradient == "none") out.gradient = "differences";
  if (!uses_gradient(o.optimizer.method)) out.gradient = "none";
  out.warnings = out.opt.warnings;
  out.converged = out.opt.converged;
  out.status = out.opt.status;
  std::tie(out.tolerance, out.tolerance_basis) = near_optimal_tolerance(p, o, out.opt.value);
  if (out.stat && o.directions_tolerance <= 0.0 && o.tolerance_resamples > 0 && can_measure_pr_tolerance(*out.stat))
    after_optimum(out, "the PR tolerance", [&] { add_measured_tolerance(p, o, out); });
  if (!x.priors.empty()) {
    out.prior_value = x.prior(out.opt.theta);
    out.prior_at = [x](const Eigen::VectorXd& t) { return x.prior(t); };
  } else {
    out.prior_at = [](const Eigen::VectorXd&) { return 0.0; };
  }
  // No overlap first: it decides whether the rest means anything, and it is cheap (one model run).
  if (out.stat)
    after_optimum(out, "the overlap check", [&] {
      Eigen::VectorXd parts = out.opt.parts.head(std::min<Eigen::Index>(out.opt.parts.size(), static_cast<Eigen::Index>(p.responses.size())));
      out.no_overlap = find_no_overlap(*out.stat, out.opt.theta, parts, o.no_overlap_pr);
      if (!out.no_overlap.empty()) {
        out.converged = false;
        out.status = "no_overlap";
        out.message = describe(out.no_overlap);
        out.warnings.insert(out.warnings.begin(), out.message);
      }
    });
  // The analyses at the optimum, in this order (their warnings follow the optimiser's).
  if (o.identifiability) after_optimum(out, "identifiability", [&] { add_identifiability(p, o, f, out); });
  if (o.optimizer.multistart > 1) after_optimum(out, "whether the starts agree", [&] { add_start_agreement(p, f, out); });
  if (o.intervals)
    after_optimum(out, "profile intervals", [&] {
      ProfileOptions po = *o.intervals;
      po.optimizer.observer = {};
      out.profile = profile_intervals(p.params, f, out.opt.theta, out.opt.value, po, oo.gradient);
      append(out.warnings, out.profile->warnings);
    });
  if (out.stat) {
    const StatisticalObjective& obj = *out.stat;
    if (!o.design.empty()) add_design_bound_warnings(o, obj, out);
    if (o.bootstrap) after_optimum(out, "bootstrap", [&] { add_bootstrap(p, o, x, obj, out); });
    if (obj.floored() > 0)
      out.warnings.push_back(fmt::format("loglik: {} predicted densities were below 1e-300 and floored (data outside the prediction)",
                                         obj.floored()));
  }
  return out;
}

}  // namespace smi::improve
