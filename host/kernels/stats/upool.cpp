// SPDX-License-Identifier: MIT
#include "kernels/stats/upool.hpp"

#include <atomic>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <thread>
#include <tuple>

#include "kernels/stats/quadrature.hpp"
#include "kernels/stats/upool_asymptotic.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::stats {
namespace {

/// ∫_a^b |u − c| du = F(b) − F(a) with F(u) = (u − c)|u − c|/2: branch-free and exact.
inline double seg(double a, double b, double c) {
  const double x = b - c, y = a - c;
  return 0.5 * (x * std::abs(x) - y * std::abs(y));
}

/// U of sorted u-values u[0..n).
inline double statistic_sorted(const double* u, int n) {
  const double inv = 1.0 / n;
  double s = seg(0.0, u[0], 0.0);
  for (int i = 1; i < n; ++i) s += seg(u[i - 1], u[i], i * inv);
  return s + seg(u[n - 1], 1.0, 1.0);
}

void check_confidence(double c) {
  if (!(c > 0.0 && c < 1.0))
    throw InvalidArgument(fmt::format("confidence must be in (0, 1), e.g. 0.95; got {}", c));
}
void check_n(int n) {
  if (n < 1) throw InvalidArgument(fmt::format("n (the number of u-values) must be >= 1, got {}", n));
}

// Fixed chunking makes the sample independent of the thread count: chunk k always draws from
// Rng(seed, k) and fills the same slots.
constexpr std::int64_t kChunk = 1 << 14;

// Sets of up to kNetMax u-values are sorted by a branch-free comparator network applied to a
// block of kLanes sets at once (structure of arrays: u[i*kLanes + lane]), so min/max run as
// SIMD over lanes and no comparison is mispredicted; larger n use std::sort per set.
constexpr int kNetMax = 32;
constexpr int kLanes = 256;

void simulate_chunk_network(int n, Rng& rng, double* out, std::int64_t count) {
  std::vector<double> u(static_cast<std::size_t>(n) * kLanes);
  double acc[kLanes];
  const double inv = 1.0 / n;
  for (std::int64_t b = 0; b < count; b += kLanes) {
    const int m = static_cast<int>(std::min<std::int64_t>(kLanes, count - b));
    const Eigen::VectorXd r = rng.uniform(static_cast<Eigen::Index>(m) * n);
    // Set k's draws are consecutive in r (same draws as the per-set order).
    for (int k = 0; k < m; ++k)
      for (int i = 0; i < n; ++i) u[static_cast<std::size_t>(i) * kLanes + k] = r[static_cast<Eigen::Index>(k) * n + i];
    // Odd-even transposition network: n rounds of disjoint neighbour comparators.
    for (int round = 0; round < n; ++round)
      for (int i = round & 1; i + 1 < n; i += 2) {
        double* a = u.data() + static_cast<std::size_t>(i) * kLanes;
        double* c = a + kLanes;
        for (int k = 0; k < kLanes; ++k) {
          const double lo = std::min(a[k], c[k]), hi = std::max(a[k], c[k]);
          a[k] = lo;
          c[k] = hi;
        }
      }
    for (int k = 0; k < kLanes; ++k) acc[k] = seg(0.0, u[static_cast<std::size_t>(k)], 0.0);
    for (int i = 1; i < n; ++i) {
      const double* a = u.data() + static_cast<std::size_t>(i - 1) * kLanes;
      const double* c = a + kLanes;
      const double lev = i * inv;
      for (int k = 0; k < kLanes; ++k) acc[k] += seg(a[k], c[k], lev);
    }
    const double* last = u.data() + static_cast<std::size_t>(n - 1) * kLanes;
    for (int k = 0; k < kLanes; ++k) acc[k] += seg(last[k], 1.0, 1.0);
    for (int k = 0; k < m; ++k) out[b + k] = acc[k];
  }
}

void simulate_chunk_sort(int n, Rng& rng, double* out, std::int64_t count, const cancel::Token& stop) {
  std::vector<double> u(static_cast<std::size_t>(n));
  for (std::int64_t r = 0; r < count; ++r) {
    if ((r & 63) == 0) stop.poll();  // one replicate sorts n values: 64 take milliseconds
    for (int i = 0; i < n; ++i) u[static_cast<std::size_t>(i)] = rng.uniform01();
    std::sort(u.begin(), u.end());
    out[r] = statistic_sorted(u.data(), n);
  }
}

std::vector<double> simulate(int n, const UpoolMcSettings& s) {
  const std::int64_t reps = s.replications;
  std::vector<double> out(static_cast<std::size_t>(reps));
  const std::int64_t chunks = (reps + kChunk - 1) / kChunk;
  std::atomic<std::int64_t> done{0};
  const cancel::Token& stop = s.stop ? *s.stop : cancel::process_token();
  auto work = [&](std::int64_t c0, std::int64_t c1) {
    for (std::int64_t c = c0; c < c1; ++c) {
      stop.poll();  // --timeout and Ctrl-C reach the Monte Carlo (it ran 49 s past --timeout 3)
      Rng rng(s.seed, static_cast<std::uint64_t>(c) + 1);
      const std::int64_t b = c * kChunk, e = std::min(reps, b + kChunk);
      if (n <= kNetMax)
        simulate_chunk_network(n, rng, out.data() + b, e - b);
      else
        simulate_chunk_sort(n, rng, out.data() + b, e - b, stop);
      if (s.progress) s.progress(static_cast<double>(++done) / static_cast<double>(chunks));
    }
  };
  // Chunks are seeded by their index, so the split over threads never changes the numbers;
  // pool::parallel_blocks caps the threads and carries a worker's exception (Interrupted) back here.
  const int nt = std::max(1, std::min<int>(s.threads, static_cast<int>(chunks)));
  pool::parallel_blocks(static_cast<Eigen::Index>(chunks), nt, 1e12,
                          [&](Eigen::Index c0, Eigen::Index c1) { work(c0, c1); }, stop);
  return out;
}

using Key = std::tuple<int, std::int64_t, std::uint64_t>;
std::mutex g_mu;
std::map<Key, std::shared_ptr<const std::vector<double>>> g_samples;
std::map<std::tuple<int, std::int64_t, std::uint64_t, double>, double> g_quantiles;

}  // namespace

double upool_statistic(ConstVec u) {
  require_size(u, 1, "u-values");
  for (Eigen::Index i = 0; i < u.size(); ++i)
    if (!(u[i] >= 0.0 && u[i] <= 1.0))
      throw InvalidArgument(fmt::format("u-values[{}] = {} is outside [0, 1]", i + 1, u[i]));
  Eigen::VectorXd s = sorted(u);
  return statistic_sorted(s.data(), static_cast<int>(s.size()));
}

std::shared_ptr<const std::vector<double>> upool_null_sample(int n, const UpoolMcSettings& s) {
  check_n(n);
  if (s.replications < kMinUpoolReplications)
    throw InvalidArgument(fmt::format("replications must be >= {}, got {}", kMinUpoolReplications, s.replications));
  const Key key{n, s.replications, s.seed};
  {
    std::lock_guard<std::mutex> lock(g_mu);
    if (auto it = g_samples.find(key); it != g_samples.end()) return it->second;
  }
  auto sample = std::make_shared<const std::vector<double>>(simulate(n, s));
  std::lock_guard<std::mutex> lock(g_mu);
  return g_samples.emplace(key, std::move(sample)).first->second;
}

double upool_threshold(int n, double confidence, const UpoolMcSettings& s) {
  check_n(n);
  check_confidence(confidence);
  if (n == 1) return 0.25 + 0.25 * confidence * confidence;  // U = (u − ½)² + ¼, |u − ½| <= c/2
  // 10^6 sets of n = 10,000 took more than 10 minutes; the fitted form is within 0.5 %.
  if (n > kUpoolMonteCarloMaxN) return upool_asymptotic_threshold(n, confidence);
  const auto qkey = std::make_tuple(n, s.replications, s.seed, confidence);
  {
    std::lock_guard<std::mutex> lock(g_mu);
    if (auto it = g_quantiles.find(qkey); it != g_quantiles.end()) return it->second;
  }
  const auto sample = upool_null_sample(n, s);
  // Type-7 quantile via two selections on a copy (no full sort).
  std::vector<double> v(*sample);
  const double h = (static_cast<double>(v.size()) - 1.0) * confidence;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(lo), v.end());
  const double a = v[lo];
  const double b = lo + 1 < v.size() ? *std::min_element(v.begin() + static_cast<std::ptrdiff_t>(lo) + 1, v.end()) : a;
  const double q = a + (h - static_cast<double>(lo)) * (b - a);
  std::lock_guard<std::mutex> lock(g_mu);
  g_quantiles[qkey] = q;
  return q;
}

double upool_pvalue(int n, double u_obs, const UpoolMcSettings& s) {
  check_n(n);
  if (n == 1) {
    // U >= u_obs  <=>  |u − ½| >= sqrt(u_obs − ¼).
    const double r = std::sqrt(std::max(0.0, u_obs - 0.25));
    return std::clamp(1.0 - 2.0 * r, 0.0, 1.0);
  }
  if (n > kUpoolMonteCarloMaxN) return upool_asymptotic_pvalue(n, u_obs);
  const auto sample = upool_null_sample(n, s);
  std::int64_t count = 0;
  for (double v : *sample) count += v >= u_obs;
  return static_cast<double>(count) / static_cast<double>(sample->size());
}

double upool_null_mean(int n) {
  check_n(n);
  // E|B/n − t| with B ~ Bin(n, t) is a polynomial in t on each [k/n, (k+1)/n]: integrate piecewise.
  auto g = [n](double t) {
    double s = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double lc = std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0);
      const double lp = (k > 0 ? k * std::log(t) : 0.0) + (n - k > 0 ? (n - k) * std::log1p(-t) : 0.0);
      s += std::exp(lc + lp) * std::abs(static_cast<double>(k) / n - t);
    }
    return s;
  };
  double m = 0.0;
  for (int k = 0; k < n; ++k) m += integrate(g, static_cast<double>(k) / n, static_cast<double>(k + 1) / n, 1e-15, 1e-14);
  return m;
}

std::string UpoolVerdict::describe() const {
  return fmt::format("u-pooling (n = {}): U = {:.4f} {} U_crit({:g}%) = {:.4f}, p = {:.4f} -> {}", n, metric,
                     pass ? "<=" : ">", confidence * 100.0, threshold, p,
                     pass ? "valid (data consistent with the prediction)" : "INVALID (data not consistent with the prediction)");
}

UpoolVerdict upool_from_u(Eigen::VectorXd u, double confidence, const UpoolMcSettings& s) {
  check_confidence(confidence);
  UpoolVerdict v;
  v.metric = upool_statistic(u);
  v.n = static_cast<int>(u.size());
  v.confidence = confidence;
  v.threshold = upool_threshold(v.n, confidence, s);
  v.p = upool_pvalue(v.n, v.metric, s);
  v.pass = v.metric <= v.threshold;
  v.u = std::move(u);
  return v;
}

UpoolVerdict upool(const std::vector<Eigen::VectorXd>& data, const std::vector<DistributionPtr>& predicted,
                   double confidence, const UpoolMcSettings& s) {
  if (data.empty()) throw InvalidArgument("data is empty: give at least one group of observations");
  if (data.size() != predicted.size())
    throw DimensionMismatch(fmt::format("data has {} groups but predicted has {}: give one predicted distribution per group",
                                        data.size(), predicted.size()));
  Eigen::Index total = 0;
  for (std::size_t j = 0; j < data.size(); ++j) {
    require_size(data[j], 1, fmt::format("data[{}]", j + 1));
    require_finite(data[j], fmt::format("data[{}]", j + 1));
    if (!predicted[j]) throw InvalidArgument(fmt::format("predicted[{}] is missing", j + 1));
    total += data[j].size();
  }
  Eigen::VectorXd u(total);
  Eigen::Index k = 0;
  for (std::size_t j = 0; j < data.size(); ++j) {
    u.segment(k, data[j].size()) = predicted[j]->cdf(data[j]);
    k += data[j].size();
  }
  return upool_from_u(std::move(u), confidence, s);
}

void upool_curve(const UpoolVerdict& v, Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const Eigen::VectorXd s = sorted(v.u);
  const Eigen::Index n = s.size();
  x.resize(2 * n + 2);
  y.resize(2 * n + 2);
  x[0] = 0.0, y[0] = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    x[2 * i + 1] = x[2 * i + 2] = s[i];
    y[2 * i + 1] = static_cast<double>(i) / static_cast<double>(n);
    y[2 * i + 2] = static_cast<double>(i + 1) / static_cast<double>(n);
  }
  x[2 * n + 1] = 1.0, y[2 * n + 1] = 1.0;
}

}  // namespace smi::stats
