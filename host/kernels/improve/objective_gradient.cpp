// The statistical objective's gradient in θ (issue 11 item 1). On common random numbers the
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

#include <cmath>

#include "kernels/core/descriptive.hpp"
#include "kernels/core/errors.hpp"
#include "kernels/core/normal.hpp"
#include "kernels/core/thread_pool.hpp"
#include "kernels/improve/input_derivatives.hpp"
#include "kernels/improve/statistical_objective.hpp"
#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/surrogate/fast_exp.hpp"

namespace smi::improve {

namespace {

constexpr double kCut = 9.0;

bool sd_based(const std::string& rule) {
  return rule == "silverman" || rule == "normal_reference" || rule == "normal" || rule == "1.06" || rule == "scott";
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

}  // namespace

bool StatisticalObjective::has_gradient() const {
  return jacobian_ && opt_.metric != MetricKind::custom && sd_based(opt_.bandwidth);
}

Evaluation StatisticalObjective::value_and_gradient(const Eigen::VectorXd& theta, Eigen::VectorXd& grad) const {
  if (!has_gradient())
    throw InvalidArgument("this calibration has no analytic gradient (it needs metric pr or loglik, an sd-based bandwidth and a model "
                          "with a gradient)");
  const Eigen::MatrixXd X = inputs_at(theta);
  const Eigen::MatrixXd Y = run_model(theta);
  const std::vector<Eigen::MatrixXd> J = jacobian_(X);
  if (J.size() != responses_.size())
    throw DimensionMismatch(fmt::format("the model's gradient covers {} responses, the calibration has {}", J.size(), responses_.size()));
  for (std::size_t r = 0; r < J.size(); ++r) {
    if (J[r].rows() != X.rows() || J[r].cols() != X.cols())
      throw DimensionMismatch(fmt::format("the model's gradient of '{}' is {}×{}, expected {}×{} (samples × inputs)", responses_[r].name,
                                          J[r].rows(), J[r].cols(), X.rows(), X.cols()));
    if (!J[r].allFinite()) throw InvalidArgument(fmt::format("the model's gradient of '{}' is not finite", responses_[r].name));
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
    if (opt_.metric == MetricKind::pr) {
      const stats::Grid& g = *r.grid;
      const Eigen::VectorXd fp = stats::kde_pdf_grid(y, h, g, opt_.threads);
      const Eigen::VectorXd& fe = f_exp_grid_[static_cast<std::size_t>(j)];
      Eigen::VectorXd ends(2);
      ends << g.lo, g.hi;
      const Eigen::VectorXd F = stats::kde_cdf(y, h, ends, 1);
      const double outside = std::max(0.0, F[0]) + std::max(0.0, 1.0 - F[1]);
      e.parts[j] = stats::l1_area_on_grid(fe, fp, g) + outside + exp_outside_[static_cast<std::size_t>(j)];
      // ∂PR/∂fp_g = −w_g sign(fe_g − fp_g), trapezoid weights w_g.
      Eigen::VectorXd a(g.n);
      for (Eigen::Index k = 0; k < g.n; ++k) {
        const double d = fe[k] - fp[k];
        a[k] = -(d > 0.0 ? 1.0 : d < 0.0 ? -1.0 : 0.0) * g.step() * (k == 0 || k == g.n - 1 ? 0.5 : 1.0);
      }
      kernel_sums(y, h, g.nodes(), a, true, gy, gh, opt_.threads);
      // Outside mass: F(x) = 1/N Σ Φ((x − y_i)/h); ∂F/∂y_i = −φ(t)/(N h), ∂F/∂h = −Σ φ(t) t/(N h).
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
    } else {
      const Eigen::VectorXd f = stats::kde_pdf(y, h, r.data, 1);
      double s = 0.0;
      Eigen::VectorXd a(f.size());
      for (Eigen::Index i = 0; i < f.size(); ++i) {
        if (!(f[i] > opt_.density_floor)) ++*floored_;
        s += std::log(std::max(f[i], opt_.density_floor));
        a[i] = f[i] > opt_.density_floor ? -1.0 / f[i] : 0.0;  // ∂(−ln f)/∂f; floored: constant
      }
      e.parts[j] = -s;
      kernel_sums(y, h, r.data, a, false, gy, gh, opt_.threads);
    }
    // Through the bandwidth h = c·sd(y): ∂h/∂y_i = c (y_i − ȳ) / ((N − 1) sd).
    const double c = h / sd, mean = y.mean();
    GY.col(j) = gy + (gh * c / ((static_cast<double>(N) - 1.0) * sd)) * (y.array() - mean).matrix();
  }
  e.value = e.parts.sum();
  // Through the model and the inputs' quantile functions.
  grad = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(params_.size()));
  const auto m = input_moments(theta);
  for (std::size_t k = 0; k < inputs_.size(); ++k) {
    const InputSpec& in = inputs_[k];
    if (in.mean_param < 0 && in.std_param < 0) continue;
    const Eigen::Index col = static_cast<Eigen::Index>(k);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(N);  // ∂objective/∂x_ik
    for (std::size_t r = 0; r < J.size(); ++r) s += GY.col(static_cast<Eigen::Index>(r)).cwiseProduct(J[r].col(col));
    const InputDerivatives d = input_derivatives(in.family, m[k].first, m[k].second, z_.col(col));
    if (in.mean_param >= 0) grad[in.mean_param] += s.dot(d.dmean);
    if (in.std_param >= 0) grad[in.std_param] += s.dot(d.dstd);
  }
  return e;
}

}  // namespace smi::improve
