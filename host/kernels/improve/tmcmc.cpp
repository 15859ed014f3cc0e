// SPDX-License-Identifier: MIT
#include "kernels/improve/tmcmc.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::improve {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Bisection steps for Δβ: halves [0, 1] down to 1e-18, below any useful tempering step.
constexpr int kBetaBisections = 60;
/// Acceptance below this in the last stage: the chains barely move, the samples repeat seeds.
constexpr double kLowAcceptance = 0.05;
/// Chains whose end points keep more than this correlation with their seeds have not mixed.
constexpr double kHighChainCorrelation = 0.5;

/// Calls the log-likelihood on the rows of T (blocks over the pool when it is thread-safe) and
/// checks every value.
class Evaluator {
 public:
  Evaluator(const BatchLogLikelihood& f, const TmcmcOptions& o, TmcmcResult& r) : f_(f), o_(o), r_(r) {}

  Eigen::VectorXd operator()(const Eigen::MatrixXd& T) {
    Eigen::VectorXd ll(T.rows());
    if (T.rows() == 0) return ll;
    const int threads = o_.callback_thread_safe ? std::max(1, o_.threads) : 1;
    const Eigen::Index blocks = threads > 1 ? std::min<Eigen::Index>(T.rows(), 4 * threads) : 1;
    const Eigen::Index per = (T.rows() + blocks - 1) / blocks;
    pool::parallel_for(static_cast<long>(blocks), threads, [&](long b) {
      const Eigen::Index lo = b * per, hi = std::min(T.rows(), lo + per);
      if (lo >= hi) return;
      const Eigen::VectorXd part = f_(T.middleRows(lo, hi - lo));
      if (part.size() != hi - lo)
        throw DimensionMismatch(fmt::format("the log-likelihood returned {} values for {} points", part.size(), hi - lo));
      ll.segment(lo, hi - lo) = part;
    });
    r_.calls += blocks;
    r_.evaluations += T.rows();
    for (Eigen::Index i = 0; i < ll.size(); ++i)
      if (std::isnan(ll[i]) || ll[i] == kInf) {
        std::string at;
        for (Eigen::Index k = 0; k < T.cols(); ++k) at += fmt::format("{}{:.6g}", k ? ", " : "", T(i, k));
        throw InvalidArgument(fmt::format("the log-likelihood returned {} at theta = ({}); it must be finite or -inf (zero likelihood)", ll[i], at));
      }
    return ll;
  }

 private:
  const BatchLogLikelihood& f_;
  const TmcmcOptions& o_;
  TmcmcResult& r_;
};

/// Coefficient of variation of w_j = exp(db (ll_j − llmax)).
double weights_cov(const Eigen::VectorXd& ll, double db, double llmax) {
  double s1 = 0.0, s2 = 0.0;
  for (Eigen::Index j = 0; j < ll.size(); ++j) {
    const double w = std::isfinite(ll[j]) ? std::exp(db * (ll[j] - llmax)) : 0.0;
    s1 += w;
    s2 += w * w;
  }
  const double n = static_cast<double>(ll.size());
  const double m = s1 / n;
  return std::sqrt(std::max(0.0, s2 / n / (m * m) - 1.0));
}

/// The tempering step: the largest Δβ <= 1 − β whose weights' COV is at most the target.
double next_step(const Eigen::VectorXd& ll, double beta, double target, double llmax) {
  const double room = 1.0 - beta;
  if (weights_cov(ll, room, llmax) <= target) return room;
  double lo = 0.0, hi = room;
  for (int i = 0; i < kBetaBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    (weights_cov(ll, mid, llmax) <= target ? lo : hi) = mid;
  }
  return std::max(lo, std::numeric_limits<double>::min());
}

/// var(mean w)/mean(w)² with the particles grouped into families (correlated within, independent
/// between): Σ_g (Σ_{j∈g} (w_j − w̄))² / (P w̄)².
double relative_variance(const Eigen::VectorXd& w, const std::vector<Eigen::Index>& family) {
  const double mean = w.mean();
  std::vector<double> total(static_cast<std::size_t>(w.size()), 0.0);
  for (Eigen::Index j = 0; j < w.size(); ++j) total[static_cast<std::size_t>(family[static_cast<std::size_t>(j)])] += w[j] - mean;
  double s = 0.0;
  for (double t : total) s += t * t;
  const double pm = static_cast<double>(w.size()) * mean;
  return s / (pm * pm);
}

/// Lower Cholesky factor of the weighted sample covariance, with a small jitter on a
/// degenerate direction (all particles equal in some parameter).
Eigen::MatrixXd proposal_factor(const Eigen::MatrixXd& X, const Eigen::VectorXd& p, const PriorSet& prior) {
  const Eigen::RowVectorXd mu = p.transpose() * X;
  const Eigen::MatrixXd D = X.rowwise() - mu;
  Eigen::MatrixXd S = D.transpose() * p.asDiagonal() * D;
  for (Eigen::Index k = 0; k < S.rows(); ++k) {
    const Prior& q = prior.priors()[static_cast<std::size_t>(k)];
    const double width = std::isfinite(q.upper - q.lower) ? q.upper - q.lower : q.std;
    const double floor = 1e-24 * width * width + 1e-300;
    S(k, k) += std::max(1e-12 * S(k, k), floor);
  }
  Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) return S.diagonal().cwiseSqrt().asDiagonal();
  return llt.matrixL();
}

/// Mean over parameters of corr(seed_k, end_k) across chains (parameters that do not vary skipped).
double chain_correlation(const Eigen::MatrixXd& seeds, const Eigen::MatrixXd& ends) {
  double sum = 0.0;
  int count = 0;
  for (Eigen::Index k = 0; k < seeds.cols(); ++k) {
    const Eigen::ArrayXd a = seeds.col(k).array() - seeds.col(k).mean();
    const Eigen::ArrayXd b = ends.col(k).array() - ends.col(k).mean();
    const double den = std::sqrt((a * a).sum() * (b * b).sum());
    if (den > 0.0) {
      sum += (a * b).sum() / den;
      ++count;
    }
  }
  return count ? sum / count : 1.0;
}

/// P indices drawn with probabilities p (multinomial: sorted uniforms against the cumulative sum).
std::vector<Eigen::Index> resample(const Eigen::VectorXd& p, Rng& rng) {
  const Eigen::Index n = p.size();
  std::vector<double> u(static_cast<std::size_t>(n));
  for (double& x : u) x = rng.uniform01();
  std::sort(u.begin(), u.end());
  std::vector<Eigen::Index> idx(static_cast<std::size_t>(n));
  double cum = p[0];
  Eigen::Index j = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    while (u[static_cast<std::size_t>(i)] > cum && j < n - 1) cum += p[++j];
    idx[static_cast<std::size_t>(i)] = j;
  }
  return idx;
}

/// The particle cloud between stages.
struct Cloud {
  Eigen::MatrixXd x;
  Eigen::VectorXd ll, lp;
  std::vector<Eigen::Index> family;  ///< the seed each particle descends from in the last resampling
};

/// Resamples the cloud by p and runs the Metropolis sweeps at temperature beta; fills the
/// stage's acceptance, sweeps, scale and chain correlation.
void move(Cloud& c, const Eigen::VectorXd& p, double beta, const PriorSet& prior, Evaluator& eval, const TmcmcOptions& o, double& scale,
          Rng& rng, TmcmcStage& st, const cancel::Token& stop) {
  const Eigen::Index n = c.x.rows(), d = c.x.cols();
  const Eigen::MatrixXd L = proposal_factor(c.x, p, prior);
  const auto idx = resample(p, rng);
  Cloud next;
  next.x.resize(n, d);
  next.ll.resize(n);
  next.lp.resize(n);
  next.family = idx;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index s = idx[static_cast<std::size_t>(i)];
    next.x.row(i) = c.x.row(s);
    next.ll[i] = c.ll[s];
    next.lp[i] = c.lp[s];
  }
  const Eigen::MatrixXd seeds = next.x;
  double moved = 0.0, accepted = 0.0;
  int sweeps = 0;
  double corr = 1.0;
  while (sweeps < o.max_sweeps && (sweeps < o.min_sweeps || moved < o.moves || corr > o.target_correlation)) {
    stop.poll();
    const Eigen::MatrixXd prop = next.x + scale * rng.normal_matrix(n, d) * L.transpose();
    const Eigen::VectorXd lp = prior.log_density(prop);
    std::vector<Eigen::Index> inside;
    for (Eigen::Index i = 0; i < n; ++i)
      if (std::isfinite(lp[i])) inside.push_back(i);
    Eigen::MatrixXd T(static_cast<Eigen::Index>(inside.size()), d);
    for (std::size_t r = 0; r < inside.size(); ++r) T.row(static_cast<Eigen::Index>(r)) = prop.row(inside[r]);
    const Eigen::VectorXd ll = eval(T);
    Eigen::VectorXd u(n);
    for (Eigen::Index i = 0; i < n; ++i) u[i] = rng.uniform01();  // one draw per chain, in or out
    long acc = 0;
    for (std::size_t r = 0; r < inside.size(); ++r) {
      const Eigen::Index i = inside[r];
      const double lli = ll[static_cast<Eigen::Index>(r)];
      if (!std::isfinite(lli)) continue;
      const double old = next.lp[i] + (std::isfinite(next.ll[i]) ? beta * next.ll[i] : -kInf);
      if (std::log(u[i]) < lp[i] + beta * lli - old) {
        next.x.row(i) = prop.row(i);
        next.ll[i] = lli;
        next.lp[i] = lp[i];
        ++acc;
      }
    }
    const double rate = static_cast<double>(acc) / static_cast<double>(n);
    moved += rate;
    accepted += rate;
    ++sweeps;
    scale *= std::exp(rate - o.target_acceptance);
    corr = chain_correlation(seeds, next.x);
  }
  st.sweeps = sweeps;
  st.acceptance = accepted / sweeps;
  st.scale = scale;
  st.chain_correlation = corr;
  c = std::move(next);
}

void validate(const TmcmcOptions& o) {
  if (o.samples < kMinParticles)
    throw InvalidArgument(fmt::format("samples must be at least {} particles, got {}", kMinParticles, o.samples));
  if (o.max_stages < 1) throw InvalidArgument(fmt::format("max_stages must be at least 1, got {}", o.max_stages));
  if (!(o.target_cov > 0.0) || !std::isfinite(o.target_cov)) throw InvalidArgument(fmt::format("target_cov must be a number > 0, got {}", o.target_cov));
  if (o.min_sweeps < 1 || o.max_sweeps < o.min_sweeps)
    throw InvalidArgument(fmt::format("sweeps: need 1 <= min_sweeps <= max_sweeps, got {} and {}", o.min_sweeps, o.max_sweeps));
  if (!(o.target_correlation > 0.0 && o.target_correlation <= 1.0))
    throw InvalidArgument(fmt::format("target_correlation must be in (0, 1], got {}", o.target_correlation));
  if (!(o.moves >= 0.0)) throw InvalidArgument(fmt::format("moves must be >= 0, got {}", o.moves));
  if (!(o.target_acceptance > 0.0 && o.target_acceptance < 1.0))
    throw InvalidArgument(fmt::format("target_acceptance must be in (0, 1), got {}", o.target_acceptance));
}

/// The converged flag's reasons from the run's last stage.
void judge(TmcmcResult& r, double beta, const TmcmcOptions& o) {
  if (beta < 1.0)
    r.reasons.push_back(fmt::format("beta reached only {:.3g} after max_stages = {} stages: raise max_stages (the data are very informative "
                                    "against the prior) or samples", beta, o.max_stages));
  const TmcmcStage& last = r.stages.back();
  if (last.acceptance < kLowAcceptance)
    r.reasons.push_back(fmt::format("acceptance {:.3f} in the last stage: the chains barely move (a posterior narrow in some direction); "
                                    "raise samples or max_sweeps", last.acceptance));
  if (last.chain_correlation > kHighChainCorrelation)
    r.reasons.push_back(fmt::format("the chains' end points keep a correlation of {:.2f} with their seeds: the samples repeat their seeds; "
                                    "raise max_sweeps or moves", last.chain_correlation));
  r.converged = r.reasons.empty();
}

}  // namespace

// long: the TMCMC loop (prior draws, then per stage: Δβ, evidence share, resample and move), one story
TmcmcResult tmcmc(const PriorSet& prior, const BatchLogLikelihood& loglik, const TmcmcOptions& o, const cancel::Token& stop) {
  validate(o);
  TmcmcResult r;
  Evaluator eval(loglik, o, r);
  Rng rng(o.seed, hash_label("smi.calibrate_bayes"));
  const Eigen::Index n = o.samples, d = prior.size();
  Cloud c;
  c.x = prior.from_uniforms(rng.uniform_matrix(n, d));
  c.lp = prior.log_density(c.x);
  stop.poll();
  c.ll = eval(c.x);
  c.family.resize(static_cast<std::size_t>(n));
  std::iota(c.family.begin(), c.family.end(), Eigen::Index{0});
  double beta = 0.0, var = 0.0;
  double scale = 2.38 / std::sqrt(static_cast<double>(d));
  while (beta < 1.0 && static_cast<int>(r.stages.size()) < o.max_stages) {
    stop.poll();
    const double llmax = c.ll.maxCoeff();
    if (!std::isfinite(llmax))
      throw InvalidArgument(r.stages.empty() ? "the likelihood is zero at every prior draw: the prior misses the data (check ranges and units)"
                                             : "the likelihood is zero at every particle");
    TmcmcStage st;
    const double db = next_step(c.ll, beta, o.target_cov, llmax);
    Eigen::VectorXd w(n);
    for (Eigen::Index j = 0; j < n; ++j) w[j] = std::isfinite(c.ll[j]) ? std::exp(db * (c.ll[j] - llmax)) : 0.0;
    st.log_mean_w = std::log(w.mean()) + db * llmax;
    st.log_z_var = relative_variance(w, c.family);
    r.log_evidence += st.log_mean_w;
    var += st.log_z_var;
    beta = std::min(1.0, beta + db);
    if (1.0 - beta < 1e-12) beta = 1.0;
    st.beta = beta;
    const Eigen::VectorXd p = w / w.sum();
    st.ess = 1.0 / p.squaredNorm();
    move(c, p, beta, prior, eval, o, scale, rng, st, stop);
    r.stages.push_back(st);
  }
  r.log_evidence_error = std::sqrt(var);
  r.samples = c.x;
  r.loglik = c.ll;
  r.logprior = c.lp;
  (r.loglik + r.logprior).maxCoeff(&r.map_index);
  judge(r, beta, o);
  return r;
}

}  // namespace smi::improve
