// SPDX-License-Identifier: MIT
// Multistart L-BFGS on ln psi in log-parameters.
#include "kernels/surrogate/ml_search.hpp"
#include "platform/core/cancel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <Eigen/QR>
#include <nlopt.hpp>
#include <numeric>
#include <vector>

#include "kernels/surrogate/doe.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::surrogate::kriging::detail {
namespace {

constexpr double kNuggetLo = 1e-10, kNuggetHi = 1.0;
constexpr double kPenalty = 1e10;  // ln psi where R is not positive definite

struct Local {
  const Problem* pb;
  Eigen::Index n;
  bool with_nugget;
  double fixed_nugget;
  int evals = 0;
  std::vector<double> best_z;
  double best = std::numeric_limits<double>::infinity();
  const cancel::Token* stop = &cancel::process_token();  ///< the run's token (ml_search's argument)

  double eval(const std::vector<double>& z, std::vector<double>& grad) {
    // NLopt turns an exception here into a stop; local() below then polls to raise the reason.
    if (stop->stop_requested()) throw nlopt::forced_stop();
    ++evals;
    Eigen::VectorXd theta(n);
    for (Eigen::Index j = 0; j < n; ++j) theta[j] = std::exp(z[j]);
    const double nug = with_nugget ? std::exp(z[n]) : fixed_nugget;
    const Factors f = factorize(*pb, theta, nug);
    if (!f.ok) {  // push towards shorter correlation lengths and more nugget: both regularise R
      for (auto& g : grad) g = -1.0;
      return kPenalty;
    }
    if (!grad.empty()) {
      const Eigen::VectorXd g = log_psi_gradient(*pb, f, theta, nug, with_nugget);
      for (Eigen::Index j = 0; j < g.size(); ++j) grad[j] = g[j];
    }
    if (f.log_psi < best) best = f.log_psi, best_z = z;
    return f.log_psi;
  }
  static double thunk(const std::vector<double>& z, std::vector<double>& grad, void* self) {
    return static_cast<Local*>(self)->eval(z, grad);
  }
};

// Candidate starts in log space: a random LHS plus the centre of the box, or the given start.
std::vector<std::vector<double>> start_candidates(const std::vector<double>& zlo, const std::vector<double>& zhi,
                                                 Eigen::Index n, bool estimate_nugget, std::uint64_t seed,
                                                 const MlResult* start) {
  const auto dim = static_cast<Eigen::Index>(zlo.size());
  const Eigen::Index ncand = start ? 1 : std::min<Eigen::Index>(20 + 5 * dim, 60);
  std::vector<std::vector<double>> cand(ncand, std::vector<double>(dim));
  if (start) {
    for (Eigen::Index j = 0; j < n; ++j) cand[0][j] = std::clamp(std::log(start->theta[j]), zlo[j], zhi[j]);
    if (estimate_nugget) cand[0][n] = std::clamp(std::log(start->nugget), zlo[n], zhi[n]);
  } else {
    Eigen::MatrixXd U = doe::lhs(ncand, dim, seed, {"none", 50, 0, false});
    U.row(0).setConstant(0.5);
    for (Eigen::Index c = 0; c < ncand; ++c)
      for (Eigen::Index j = 0; j < dim; ++j) cand[c][j] = zlo[j] + (zhi[j] - zlo[j]) * U(c, j);
  }
  return cand;
}

// How many local searches, and whether they go in confirming rounds. Automatic: 8 / 4 / 2
// local searches from the best candidates by size. Small designs run all 8: their likelihood is
// often multimodal with the best basin reached from few starts (spec 8.4's 2-D example: 1 start
// in 8) and their evaluations are cheap. Above m = 150 the searches go in rounds of two (one
// per core) and stop as soon as the best optimum has been reached from two different starts.
// Given `starts`: exactly that many. The rounds do not depend on the thread count, so neither
// does the result.
int local_search_count(const Problem& pb, int starts, const std::vector<double>& cval, bool& confirm) {
  const int m = static_cast<int>(pb.m());
  confirm = starts <= 0 && m > 150;
  if (starts <= 0) starts = m <= 150 ? 8 : (m <= 400 ? 4 : 2);
  starts = std::min<int>(starts, static_cast<int>(cval.size()));
  if (confirm) {
    // Starts no better than uncorrelated points (theta -> infinity: R = I, psi = the
    // least-squares residual variance) sit on the plateau where the gradient vanishes and a
    // local search stalls: beyond the first round, only candidates below it are searched.
    const Eigen::VectorXd res0 = pb.Y - pb.F * pb.F.colPivHouseholderQr().solve(pb.Y);
    const double plateau = std::log(std::max(res0.squaredNorm() / static_cast<double>(m),
                                             std::numeric_limits<double>::min())) - 1e-3;
    const int below = static_cast<int>(std::count_if(cval.begin(), cval.end(), [&](double v) { return v < plateau; }));
    starts = std::min(starts, std::max(2, below));
  }
  return starts;
}

// One L-BFGS search from z; loc keeps the best point it saw.
void local_search(Local& loc, std::vector<double> z, const std::vector<double>& zlo, const std::vector<double>& zhi,
                  int maxeval, const cancel::Token& stop) {
  nlopt::opt opt(nlopt::LD_LBFGS, static_cast<unsigned>(zlo.size()));
  opt.set_lower_bounds(zlo);
  opt.set_upper_bounds(zhi);
  opt.set_min_objective(&Local::thunk, &loc);
  opt.set_ftol_rel(1e-9);
  opt.set_xtol_rel(1e-6);
  opt.set_maxeval(maxeval);
  double fz = 0;
  try {
    opt.optimize(z, fz);
  } catch (const std::exception&) {
    // roundoff_limited and friends: the best point seen so far stands
  }
  stop.poll();  // a forced stop for --timeout / Ctrl-C: raise it, do not keep the point
}

// Confirming rounds end once the best optimum has been reached from two different starts.
bool best_reached_twice(const std::vector<Local>& runs, int done) {
  double fbest = std::numeric_limits<double>::infinity();
  for (int r = 0; r < done; ++r) fbest = std::min(fbest, runs[r].best);
  int hits = 0;
  for (int r = 0; r < done; ++r)
    if (runs[r].best <= fbest + 1e-6 * std::max(1.0, std::abs(fbest))) ++hits;
  return hits >= 2 && fbest < kPenalty;
}

}  // namespace

MlResult ml_search(const Problem& pb, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double nugget,
                   bool estimate_nugget, int starts, std::uint64_t seed, int threads, const MlResult* start,
                   int maxeval, const cancel::Token& stop) {
  const Eigen::Index n = lower.size(), dim = n + (estimate_nugget ? 1 : 0);
  std::vector<double> zlo(dim), zhi(dim);
  for (Eigen::Index j = 0; j < n; ++j) zlo[j] = std::log(lower[j]), zhi[j] = std::log(upper[j]);
  if (estimate_nugget) zlo[n] = std::log(kNuggetLo), zhi[n] = std::log(kNuggetHi);

  const std::vector<std::vector<double>> cand = start_candidates(zlo, zhi, n, estimate_nugget, seed, start);
  const auto ncand = static_cast<Eigen::Index>(cand.size());
  std::vector<double> cval(ncand);
  std::vector<int> cevals(ncand, 0);
  pool::parallel_for(ncand, threads, [&](long c) {
    Local loc{&pb, n, estimate_nugget, nugget, 0, {}, std::numeric_limits<double>::infinity(), &stop};
    std::vector<double> nograd;
    cval[c] = loc.eval(cand[c], nograd);
    cevals[c] = loc.evals;
  }, stop);
  std::vector<long> order(ncand);
  std::iota(order.begin(), order.end(), 0L);
  std::stable_sort(order.begin(), order.end(), [&](long a, long b) { return cval[a] < cval[b]; });

  const int m = static_cast<int>(pb.m());
  bool confirm = false;
  starts = local_search_count(pb, starts, cval, confirm);
  const int round = confirm ? 2 : starts;
  std::vector<Local> runs(starts, Local{&pb, n, estimate_nugget, nugget, 0, {}, std::numeric_limits<double>::infinity(), &stop});
  auto local = [&](long r) { local_search(runs[r], cand[order[r]], zlo, zhi, maxeval > 0 ? maxeval : (m > 500 ? 80 : 150), stop); };
  int done = 0;
  while (done < starts) {
    const int k = std::min(round, starts - done);
    pool::parallel_for(k, threads, [&](long r) { local(done + r); }, stop);
    done += k;
    if (confirm && best_reached_twice(runs, done)) break;
  }
  runs.resize(done);
  MlResult res;
  std::vector<double> best = cand[order[0]];
  res.log_psi = cval[order[0]];
  for (auto& r : runs) {
    res.evaluations += r.evals;
    if (r.best < res.log_psi) res.log_psi = r.best, best = r.best_z;
  }
  for (int e : cevals) res.evaluations += e;
  res.theta.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) res.theta[j] = std::exp(best[j]);
  res.nugget = estimate_nugget ? std::exp(best[n]) : nugget;
  return res;
}

}  // namespace smi::surrogate::kriging::detail
