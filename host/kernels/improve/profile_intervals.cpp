// SPDX-License-Identifier: MIT
#include "kernels/improve/profile_intervals.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "kernels/stats/special.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"

namespace smi::improve {

double likelihood_ratio_delta(double level) {
  if (!(level > 0.0 && level < 1.0)) throw InvalidArgument(fmt::format("interval level must be in (0, 1), got {}", level));
  const double z = normal_quantile(0.5 * (1.0 + level));
  return 0.5 * z * z;
}

double likelihood_ratio_delta(double level, int observations, int parameters) {
  (void)likelihood_ratio_delta(level);  // checks the level
  if (observations <= parameters)
    throw InvalidArgument(fmt::format("intervals: {} observations for {} parameters: the small-sample delta needs more observations than "
                                      "parameters (leave observations out for the plain likelihood-ratio interval)", observations, parameters));
  const double m = static_cast<double>(observations - parameters);
  const double t = stats::student_t_quantile(0.5 * (1.0 + level), m);
  return 0.5 * static_cast<double>(observations) * std::log1p(t * t / m);
}

namespace {

/// min over the other parameters with parameter i held at v, from `from` (updated to the argmin).
double profile_at(const std::vector<Parameter>& params, const Objective& f, const ObjectiveGradient& gradient, Eigen::Index i, double v,
                  Eigen::VectorXd& from, const OptimizerOptions& oo, int& evaluations) {
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  auto full = [i, v, k](const Eigen::VectorXd& r) {
    Eigen::VectorXd t(k);
    for (Eigen::Index j = 0, q = 0; j < k; ++j) t[j] = j == i ? v : r[q++];
    return t;
  };
  if (k == 1) {
    ++evaluations;
    from[0] = v;
    return f(full(Eigen::VectorXd())).value;
  }
  std::vector<Parameter> rest;
  for (Eigen::Index j = 0; j < k; ++j)
    if (j != i) {
      Parameter p = params[static_cast<std::size_t>(j)];
      p.start = std::clamp(from[j], p.lower, p.upper);
      rest.push_back(p);
    }
  OptimizerOptions o = oo;
  o.multistart = 1;
  o.observer = {};
  o.prepare_start = {};
  o.gradient = {};
  if (gradient)
    o.gradient = [&gradient, &full, i](const Eigen::VectorXd& r, Eigen::VectorXd& g) {
      Eigen::VectorXd gf;
      const Evaluation e = gradient(full(r), gf);
      g.resize(r.size());
      for (Eigen::Index j = 0, q = 0; j < gf.size(); ++j)
        if (j != i) g[q++] = gf[j];
      return e;
    };
  const OptimizationResult res = minimize(rest, [&f, &full](const Eigen::VectorXd& r) { return f(full(r)); }, o);
  evaluations += res.evaluations;
  from = full(res.theta);
  return res.value;
}

}  // namespace

ProfileResult profile_intervals(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum, double value,
                                const ProfileOptions& opt, const ObjectiveGradient& gradient) {
  validate_parameters(params);
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  if (optimum.size() != k) throw DimensionMismatch(fmt::format("optimum has {} values for {} parameters", optimum.size(), k));
  if (!(opt.delta > 0.0) || !std::isfinite(opt.delta)) throw InvalidArgument(fmt::format("profile delta must be > 0, got {}", opt.delta));
  ProfileResult out;
  for (Eigen::Index i = 0; i < k; ++i) {
    const Parameter& p = params[static_cast<std::size_t>(i)];
    const double range = p.upper - p.lower, x0 = optimum[i];
    std::map<double, double> prof{{x0, value}};
    // First step from the curvature along the parameter (others fixed, an upper bound on the
    // profile's): about half the predicted distance to the crossing.
    const double h = 1e-3 * range;
    Eigen::VectorXd tp = optimum, tm = optimum;
    tp[i] = std::min(p.upper, x0 + h);
    tm[i] = std::max(p.lower, x0 - h);
    const double fp = f(tp).value, fm = f(tm).value;
    out.evaluations += 2;
    const double curv = (fp - 2 * value + fm) / (0.25 * (tp[i] - tm[i]) * (tp[i] - tm[i]));
    double step = curv > 0 ? 0.5 * std::sqrt(2 * opt.delta / curv) : 0.1 * range;
    step = std::clamp(step, 1e-4 * range, 0.2 * range);
    ProfileInterval iv;
    for (int dir : {-1, 1}) {
      const double bound = dir < 0 ? p.lower : p.upper;
      Eigen::VectorXd from = optimum;
      double ok = x0, bad = x0;
      bool crossed = false;
      double s = step;
      for (int j = 0; j < opt.max_steps && ok != bound; ++j) {
        const double v = dir < 0 ? std::max(bound, ok - s) : std::min(bound, ok + s);
        const double pv = profile_at(params, f, gradient, i, v, from, opt.optimizer, out.evaluations);
        prof[v] = pv;
        if (pv - value > opt.delta) {
          bad = v;
          crossed = true;
          break;
        }
        ok = v;
        s *= 1.6;  // the profile may be flatter than the curvature says
      }
      if (crossed) {
        Eigen::VectorXd from_ok = from;
        for (int it = 0; it < opt.bisections; ++it) {
          const double v = 0.5 * (ok + bad);
          const double pv = profile_at(params, f, gradient, i, v, from_ok, opt.optimizer, out.evaluations);
          prof[v] = pv;
          (pv - value > opt.delta ? bad : ok) = v;
        }
        // linear interpolation of the crossing between the last two points
        const double fo = prof[ok] - value, fb = prof[bad] - value;
        const double x = fb > fo ? ok + (bad - ok) * (opt.delta - fo) / (fb - fo) : ok;
        (dir < 0 ? iv.lower : iv.upper) = x;
      } else {
        (dir < 0 ? iv.lower : iv.upper) = ok;
        (dir < 0 ? iv.lower_open : iv.upper_open) = ok == bound;
        if (ok != bound)
          out.warnings.push_back(fmt::format("profile of '{}': no crossing within {} steps on the {} side; the interval stops at {}", p.name,
                                             opt.max_steps, dir < 0 ? "lower" : "upper", ok));
      }
    }
    iv.determined = !(iv.lower_open && iv.upper_open);
    if (!iv.determined)
      out.warnings.push_back(fmt::format("parameter '{}' is not determined by the data: its profile stays within {:.3g} of the optimum "
                                         "over its whole range [{}, {}]", p.name, opt.delta, p.lower, p.upper));
    iv.nodes.resize(static_cast<Eigen::Index>(prof.size()));
    iv.values.resize(iv.nodes.size());
    Eigen::Index q = 0;
    for (const auto& [x, v] : prof) {
      iv.nodes[q] = x;
      iv.values[q++] = v;
    }
    out.intervals.push_back(std::move(iv));
  }
  return out;
}

}  // namespace smi::improve
