// SPDX-License-Identifier: MIT
// The statistical objective's gradient in θ. On common random numbers the
// objective is a smooth function of the distribution parameters:
//   θ -> X = Q(Φ(Z); θ) -> Y = model(X) -> KDE of each response (bandwidth c·sd(y)) -> metric.
// Each link's derivative is analytic: input_derivatives (quantile functions), the model's
// Jacobian (Kriging: closed form), and here the KDE and the metric:
//   PR   = Σ_g w_g |fe_g − fp_g| + F(lo) + 1 − F(hi) (+ f_exp's mass outside, constant)
//   fp_g = 1/(N h) Σ_i φ(t_gi),  t_gi = (x_g − y_i)/h
//   ∂fp_g/∂y_i = φ(t) t / (N h²),  ∂fp_g/∂h = Σ_i φ(t)(t² − 1) / (N h²)
//   loglik = −Σ_k ln f(d_k) with the same kernel sums at the data points.
// The sums over grid nodes (or data) × samples cost about one forward KDE pass; terms with
// |t| > 9 (φ < 3e-18 relative) are skipped.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "kernels/improve/input_derivatives.hpp"
#include "kernels/improve/statistical_objective.hpp"
#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_coarse_grid.hpp"
#include "kernels/stats/kde_uniform_grid.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/surrogate/fast_exp.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::improve {

namespace {

constexpr double kCut = 9.0;

bool sd_based(const std::string& rule) {
  return rule == "silverman" || rule == "normal_reference" || rule == "normal" || rule == "1.06" || rule == "scott";
}
bool robust_rule(const std::string& rule) { return rule == "robust" || rule == "silverman_robust"; }
bool mad_rule(const std::string& rule) { return rule == "mad" || rule == "matlab"; }

/// Adds scale · ∂q/∂x_i of the sample p-quantile (linear interpolation between order statistics,
/// core/descriptive's quantile_sorted) to out: 1 − frac at the lower order statistic, frac at the
/// upper. `order` sorts x ascending.
void add_quantile_weights(const std::vector<Eigen::Index>& order, double p, double scale, Eigen::VectorXd& out) {
  const Eigen::Index n = static_cast<Eigen::Index>(order.size());
  const double h = (static_cast<double>(n) - 1.0) * p;
  const auto lo = static_cast<Eigen::Index>(std::floor(h));
  const Eigen::Index hi = std::min<Eigen::Index>(lo + 1, n - 1);
  const double frac = h - static_cast<double>(lo);
  out[order[static_cast<std::size_t>(lo)]] += scale * (1.0 - frac);
  out[order[static_cast<std::size_t>(hi)]] += scale * frac;
}

std::vector<Eigen::Index> argsort(const Eigen::VectorXd& x) {
  std::vector<Eigen::Index> o(static_cast<std::size_t>(x.size()));
  for (std::size_t i = 0; i < o.size(); ++i) o[i] = static_cast<Eigen::Index>(i);
  std::stable_sort(o.begin(), o.end(), [&x](Eigen::Index a, Eigen::Index b) { return x[a] < x[b]; });
  return o;
}

/// ∂h/∂y_i of the bandwidth rule at y. sd-based rules h = c·sd: c (y_i − ȳ)/((N − 1) sd).
/// "robust" 0.9 min(sd, IQR/1.34) N^−0.2 and "mad" (MAD/0.6745)(4/(3N))^0.2 go through the order
/// statistics their quantiles interpolate: piecewise linear in y, so the derivative is exact
/// wherever no two samples swap order (almost everywhere on CRN), as the rules themselves are.
Eigen::VectorXd bandwidth_gradient(const Eigen::VectorXd& y, const std::string& rule, double h) {
  const Eigen::Index N = y.size();
  const double n = static_cast<double>(N), sd = stddev(y), mean = y.mean();
  const Eigen::VectorXd dsd = (y.array() - mean).matrix() / ((n - 1.0) * sd);
  if (sd_based(rule)) return (h / sd) * dsd;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(N);
  const std::vector<Eigen::Index> order = argsort(y);
  if (robust_rule(rule)) {
    const double c = 0.9 * std::pow(n, -0.2);
    const Eigen::VectorXd s = sorted(y);
    const double iqr = quantile_sorted(s, 0.75) - quantile_sorted(s, 0.25);
    if (!(iqr > 0.0) || sd <= iqr / 1.34) return c * dsd;
    add_quantile_weights(order, 0.75, c / 1.34, g);
    add_quantile_weights(order, 0.25, -c / 1.34, g);
    return g;
  }
  // mad: MAD = median_k |y_k − m|, m = median(y): ∂MAD/∂y_i = Σ_k w_k sign(y_k − m)(δ_ik − ∂m/∂y_i).
  const double c = std::pow(4.0 / (3.0 * n), 0.2);
  Eigen::VectorXd dm = Eigen::VectorXd::Zero(N);
  add_quantile_weights(order, 0.5, 1.0, dm);
  const double m = quantile_sorted(sorted(y), 0.5);
  const Eigen::VectorXd dev = (y.array() - m).abs().matrix();
  const double md = quantile_sorted(sorted(dev), 0.5);
  if (!(md > 0.0)) {  // the rule falls back to the range
    g[order.back()] += c;
    g[order.front()] -= c;
    return g;
  }
  Eigen::VectorXd wd = Eigen::VectorXd::Zero(N);
  add_quantile_weights(argsort(dev), 0.5, 1.0, wd);
  for (Eigen::Index k = 0; k < N; ++k) {
    if (wd[k] == 0.0) continue;
    const double sk = y[k] > m ? 1.0 : (y[k] < m ? -1.0 : 0.0);
    g[k] += wd[k] * sk;
    g -= (wd[k] * sk) * dm;
  }
  return (c / 0.6745) * g;
}

/// ∂metric/∂y_i and ∂metric/∂h of one response, given a_g = ∂metric/∂(kernel sum at point x_g)
/// scaled so that the metric's derivative through point g is a_g · (that derivative of fp_g).
/// Returns gy (N) and adds to gh.
void kernel_sums(const Eigen::VectorXd& y, double h, const Eigen::VectorXd& x, const Eigen::VectorXd& a, bool sorted_x,
                 Eigen::VectorXd& gy, double& gh, int threads) {
  const Eigen::Index N = y.size(), G = x.size();
  const double norm = kInvSqrt2Pi / (static_cast<double>(N) * h * h);
  gy.resize(N);
  constexpr Eigen::Index kBlock = 256;
  const long nb = static_cast<long>((N + kBlock - 1) / kBlock);
  std::vector<double> ghs(static_cast<std::size_t>(nb), 0.0);
  const double lo = G > 0 ? x[0] : 0.0, step = G > 1 ? (x[G - 1] - x[0]) / static_cast<double>(G - 1) : 1.0;
  pool::parallel_for(nb, threads, [&](long b) {
    double acc_h = 0.0;
    Eigen::ArrayXd t, e;  // per sample: the window's standardised distances and kernels
    for (Eigen::Index i = b * kBlock; i < std::min(N, (b + 1) * kBlock); ++i) {
      Eigen::Index g0 = 0, g1 = G;
      if (sorted_x && step > 0.0) {  // a uniform grid: only nodes within kCut·h of y_i
        g0 = std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::floor((y[i] - kCut * h - lo) / step)));
        g1 = std::min<Eigen::Index>(G, static_cast<Eigen::Index>(std::ceil((y[i] + kCut * h - lo) / step)) + 1);
      }
      if (g1 <= g0) {
        gy[i] = 0.0;
        continue;
      }
      t = (x.segment(g0, g1 - g0).array() - y[i]) / h;
      e = 0.5 * t.square();
      smi::surrogate::kriging::exp_neg_inplace(e.data(), static_cast<long>(e.size()));  // vectorised exp(−t²/2)
      e *= a.segment(g0, g1 - g0).array();
      gy[i] = norm * (e * t).sum();
      acc_h += (e * (t.square() - 1.0)).sum();
    }
    ghs[static_cast<std::size_t>(b)] = acc_h;
  });
  for (double v : ghs) gh += norm * v;
}

/// kernel_sums on a uniform grid with step dx <= h/4 (the PR grids), exactly the same sums
/// (to rounding) at a fraction of the cost: inside a block of 64 nodes starting at z0 = (x_b − y)/h,
///   e_j = φ(z0 + jδ)√(2π) = e^{−z0²/2} · g^j · H_j,  g = e^{−z0 δ},  H_j = e^{−δ²j²/2},
/// so Σ_j a_j e_j z_j = P (z0 S0 + δ S1) and Σ_j a_j e_j (z_j² − 1) = P ((z0² − 1) S0 + 2 z0 δ S1
/// + δ² S2) with S_p = Σ_j g^j (H_j j^p a_j): the bracketed weights are per block, shared by all
/// samples, and g^j = (g⁸)^{j/8} g^{j mod 8} takes 16 multiplications (in range up to δ = 1/4:
/// kde_uniform_grid.hpp). Two exponentials and
/// about 4 flops per node instead of an exponential per node; whole blocks within kCut·h of y
/// (up to 64 nodes more than the plain window, only more exact). Samples are independent, so the
/// result does not depend on the thread count.
void kernel_sums_uniform(const Eigen::VectorXd& y, double h, double lo, double dx, Eigen::Index G, const Eigen::VectorXd& a,
                         Eigen::VectorXd& gy, double& gh, int threads) {
  constexpr Eigen::Index B = 64;
  const Eigen::Index N = y.size(), nblk = (G + B - 1) / B;
  const double ih = 1.0 / h, d = dx * ih;
  const double norm = kInvSqrt2Pi / (static_cast<double>(N) * h * h);
  // Per block weights A_p[j] = H_j j^p a_{bB+j}, zero past the last node.
  std::vector<double> A(static_cast<std::size_t>(3 * B * nblk), 0.0);
  for (Eigen::Index b = 0; b < nblk; ++b)
    for (Eigen::Index j = 0; j < B && b * B + j < G; ++j) {
      const double hj = std::exp(-0.5 * d * d * static_cast<double>(j * j)) * a[b * B + j];
      double* base = A.data() + 3 * B * b;
      base[j] = hj;
      base[B + j] = hj * static_cast<double>(j);
      base[2 * B + j] = hj * static_cast<double>(j * j);
    }
  gy.resize(N);
  constexpr Eigen::Index kSamples = 256;
  const long nb = static_cast<long>((N + kSamples - 1) / kSamples);
  std::vector<double> ghs(static_cast<std::size_t>(nb), 0.0);
  pool::parallel_for(nb, threads, [&](long sb) {
    double acc_h = 0.0;
    for (Eigen::Index i = sb * kSamples; i < std::min(N, (sb + 1) * kSamples); ++i) {
      const double u0 = (y[i] - kCut * h - lo) / dx, u1 = (y[i] + kCut * h - lo) / dx;
      const Eigen::Index b0 = std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::floor(u0 / B)));
      const Eigen::Index b1 = std::min<Eigen::Index>(nblk, static_cast<Eigen::Index>(std::floor(u1 / B)) + 1);
      double sy = 0.0;
      for (Eigen::Index b = b0; b < b1; ++b) {
        const double z0 = (lo + static_cast<double>(b * B) * dx - y[i]) * ih;
        const double g = std::exp(-z0 * d), P = std::exp(-0.5 * z0 * z0);
        double p1[8], p8[8];
        p1[0] = 1.0;
        for (int k = 1; k < 8; ++k) p1[k] = p1[k - 1] * g;
        const double g8 = p1[7] * g;
        p8[0] = 1.0;
        for (int m = 1; m < 8; ++m) p8[m] = p8[m - 1] * g8;
        const double* A0 = A.data() + 3 * B * b;
        const double *A1 = A0 + B, *A2 = A0 + 2 * B;
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (int m = 0; m < 8; ++m) {
          double q0 = 0.0, q1 = 0.0, q2 = 0.0;
          for (int k = 0; k < 8; ++k) {
            q0 += p1[k] * A0[8 * m + k];
            q1 += p1[k] * A1[8 * m + k];
            q2 += p1[k] * A2[8 * m + k];
          }
          s0 += p8[m] * q0;
          s1 += p8[m] * q1;
          s2 += p8[m] * q2;
        }
        sy += P * (z0 * s0 + d * s1);
        acc_h += P * ((z0 * z0 - 1.0) * s0 + 2.0 * z0 * d * s1 + d * d * s2);
      }
      gy[i] = norm * sy;
    }
    ghs[static_cast<std::size_t>(sb)] = acc_h;
  });
  for (double v : ghs) gh += norm * v;
}

/// PR's outside-mass terms F(lo) + 1 − F(hi) (each only where it is positive, as the value
/// clamps them) added to gy and gh: F(x) = 1/N Σ Φ((x − y_i)/h), so ∂F/∂y_i = −φ(t)/(N h) and
/// ∂F/∂h = −Σ φ(t) t/(N h). `F` holds the KDE's CDF at lo and hi.
void add_outside_mass_gradient(const Eigen::VectorXd& y, double h, const stats::Grid& g, const Eigen::VectorXd& F, Eigen::VectorXd& gy, double& gh) {
  const Eigen::Index N = y.size();
  const double n = static_cast<double>(N);
  for (Eigen::Index i = 0; i < N; ++i) {
    const double tl = (g.lo - y[i]) / h, th = (g.hi - y[i]) / h;
    const double pl = normal_pdf(tl), ph = normal_pdf(th);
    if (F[0] > 0.0) {
      gy[i] += -pl / (n * h);
      gh += -pl * tl / (n * h);
    }
    if (1.0 - F[1] > 0.0) {
      gy[i] += ph / (n * h);
      gh += ph * th / (n * h);
    }
  }
}

/// One response's PR (L1 area between f_exp `fe` and the KDE of y on grid g, plus both
/// densities' mass outside the grid; `exp_outside` is f_exp's, a constant) and its gradient in
/// y (set in gy) and in the bandwidth h (added to gh).
double pr_part_and_gradient(const Eigen::VectorXd& y, double h, const stats::Grid& g, const Eigen::VectorXd& fe, double exp_outside, int threads,
                            Eigen::VectorXd& gy, double& gh) {
  const auto coarse = stats::coarse_grid(g, h);  // an over-resolved grid: sums on a coarser one (kde_coarse_grid.hpp)
  const Eigen::VectorXd fp = stats::kde_pdf_resolved(y, h, g, coarse, threads);
  Eigen::VectorXd ends(2);
  ends << g.lo, g.hi;
  const Eigen::VectorXd F = stats::kde_cdf(y, h, ends, 1);
  const double outside = std::max(0.0, F[0]) + std::max(0.0, 1.0 - F[1]);
  const double part = stats::l1_area_on_grid(fe, fp, g) + outside + exp_outside;
  // ∂PR/∂fp_g = −w_g sign(fe_g − fp_g), trapezoid weights w_g.
  Eigen::VectorXd a(g.n);
  for (Eigen::Index k = 0; k < g.n; ++k) {
    const double d = fe[k] - fp[k];
    a[k] = -(d > 0.0 ? 1.0 : d < 0.0 ? -1.0 : 0.0) * g.step() * (k == 0 || k == g.n - 1 ? 0.5 : 1.0);
  }
  if (coarse)  // the exact gradient of the interpolated values: the weights carried to the coarse nodes
    kernel_sums_uniform(y, h, coarse->coarse.lo, coarse->coarse.step(), coarse->coarse.n, stats::interpolate_adjoint(*coarse, a), gy, gh, threads);
  else if (g.step() <= h * stats::detail::kUniformPdfMaxStep)
    kernel_sums_uniform(y, h, g.lo, g.step(), g.n, a, gy, gh, threads);
  else
    kernel_sums(y, h, g.nodes(), a, true, gy, gh, threads);
  add_outside_mass_gradient(y, h, g, F, gy, gh);
  return part;
}

/// One response's negative log-likelihood of its data under the KDE of y (densities below
/// `floor` are floored, counted in `floored`, and contribute no gradient) and its gradient in y
/// (set in gy) and in the bandwidth h (added to gh).
double loglik_part_and_gradient(const Eigen::VectorXd& y, double h, const Eigen::VectorXd& data, double floor, std::atomic<long>& floored,
                                int threads, Eigen::VectorXd& gy, double& gh) {
  const Eigen::VectorXd f = stats::kde_pdf(y, h, data, 1);
  double s = 0.0;
  Eigen::VectorXd a(f.size());
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    if (!(f[i] > floor)) ++floored;
    s += std::log(std::max(f[i], floor));
    a[i] = f[i] > floor ? -1.0 / f[i] : 0.0;  // ∂(−ln f)/∂f; floored: constant
  }
  kernel_sums(y, h, data, a, false, gy, gh, threads);
  return -s;
}

/// The chain rule's last links: from ∂objective/∂y (GY, samples × responses) through the model's
/// Jacobian J (one samples × inputs matrix per response) to ∂objective/∂x, then through each
/// input's quantile function (its derivatives in the mean and std at the CRN column z) to θ.
/// `moments` are the inputs' (mean, std) at θ; grad is set to the gradient, `n_params` long.
void chain_to_parameters(const std::vector<InputSpec>& inputs, const Eigen::MatrixXd& z, const std::vector<std::pair<double, double>>& moments,
                         const Eigen::MatrixXd& GY, const std::vector<Eigen::MatrixXd>& J, Eigen::Index n_params, Eigen::VectorXd& grad) {
  grad = Eigen::VectorXd::Zero(n_params);
  const Eigen::Index N = GY.rows();
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const InputSpec& in = inputs[k];
    if (in.mean_param < 0 && in.std_param < 0) continue;
    const Eigen::Index col = static_cast<Eigen::Index>(k);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(N);  // ∂objective/∂x_ik
    for (std::size_t r = 0; r < J.size(); ++r) s += GY.col(static_cast<Eigen::Index>(r)).cwiseProduct(J[r].col(col));
    const InputDerivatives d = input_derivatives(in.family, moments[k].first, moments[k].second, z.col(col));
    if (in.mean_param >= 0) grad[in.mean_param] += s.dot(d.dmean);
    if (in.std_param >= 0) grad[in.std_param] += s.dot(d.dstd);
  }
}

}  // namespace

bool StatisticalObjective::has_gradient() const {
  return (jacobian_ || diff_step_ > 0.0) && opt_.metric != MetricKind::custom && (sd_based(opt_.bandwidth) || robust_rule(opt_.bandwidth) || mad_rule(opt_.bandwidth));
}

std::vector<Eigen::MatrixXd> StatisticalObjective::model_jacobian(const Eigen::MatrixXd& X) const {
  if (!jacobian_) throw InvalidArgument("the model has no gradient (an smi.kriging, or an object with m:gradient(X), has one)");
  const std::vector<Eigen::MatrixXd> J = jacobian_(X);
  if (J.size() != responses_.size())
    throw DimensionMismatch(fmt::format("the model's gradient covers {} responses, the calibration has {}", J.size(), responses_.size()));
  for (std::size_t r = 0; r < J.size(); ++r) {
    if (J[r].rows() != X.rows() || J[r].cols() != X.cols())
      throw DimensionMismatch(fmt::format("the model's gradient of '{}' is {}×{}, expected {}×{} (samples × inputs)", responses_[r].name,
                                          J[r].rows(), J[r].cols(), X.rows(), X.cols()));
    if (!J[r].allFinite()) throw InvalidArgument(fmt::format("the model's gradient of '{}' is not finite", responses_[r].name));
  }
  return J;
}

Evaluation StatisticalObjective::value_and_gradient(const Eigen::VectorXd& theta, Eigen::VectorXd& grad) const {
  if (!has_gradient())
    throw InvalidArgument("this calibration has no analytic gradient (it needs metric pr or loglik, a bandwidth rule other than lscv and sj, "
                          "and a model "
                          "with a gradient)");
  const Eigen::MatrixXd X = inputs_at(theta);
  Eigen::MatrixXd Y;
  std::vector<Eigen::MatrixXd> J;
  if (jacobian_) {
    Y = run_model(theta);
    J = model_jacobian(X);
  } else {
    std::tie(Y, J) = differences(theta, X);
  }

  const Eigen::Index N = Y.rows();
  Evaluation e;
  e.parts.resize(Y.cols());
  Eigen::MatrixXd GY(N, Y.cols());  // ∂objective/∂y per response
  for (Eigen::Index j = 0; j < Y.cols(); ++j) {
    const ResponseSpec& r = responses_[static_cast<std::size_t>(j)];
    const Eigen::VectorXd y = Y.col(j);
    const double sd = stddev(y);
    if (!(sd > 0.0))
      throw InvalidArgument(fmt::format("response '{}': the model output is constant ({}) over the CRN sample, so it has no density "
                                        "(check that the calibrated inputs reach the model)", r.name, y[0]));
    const double h = stats::bandwidth_by_name(y, opt_.bandwidth);
    Eigen::VectorXd gy;
    double gh = 0.0;
    if (opt_.metric == MetricKind::pr)
      e.parts[j] = pr_part_and_gradient(y, h, *r.grid, f_exp_grid_[static_cast<std::size_t>(j)], exp_outside_[static_cast<std::size_t>(j)],
                                        opt_.threads, gy, gh);
    else
      e.parts[j] = loglik_part_and_gradient(y, h, r.data, opt_.density_floor, *floored_, opt_.threads, gy, gh);
    // Through the bandwidth: ∂objective/∂y_i += ∂objective/∂h · ∂h/∂y_i.
    GY.col(j) = gy + gh * bandwidth_gradient(y, opt_.bandwidth, h);
  }
  e.value = e.parts.sum();
  // Through the model and the inputs' quantile functions.
  chain_to_parameters(inputs_, z_, input_moments(theta), GY, J, static_cast<Eigen::Index>(params_.size()), grad);
  return e;
}

}  // namespace smi::improve
