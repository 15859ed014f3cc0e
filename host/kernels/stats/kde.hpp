// SPDX-License-Identifier: MIT
#pragma once
// Gaussian kernel density estimate (spec §0):
//   f(y) = 1/(N h) Σ φ((y − t_i)/h),   F(y) = 1/N Σ Φ((y − t_i)/h).
// Exact sums over sorted data, skipping kernels beyond ±kCutoff·h (each skipped term is
// below 1e-17 of a kernel's peak), vectorised with Eigen and split over 2 threads for large
// jobs (deterministic: every output element is computed by one thread in a fixed order).
// Uniformly spaced x finer than h/4 (pdf) or h/256 (cdf) take the near exp-free recurrences
// of kde_uniform_grid.hpp (same values to ~1e-13).
// A binned fast path (linear binning + exact Gaussian weights on a uniform bin grid) is used
// automatically when N·M is large; its absolute error is bounded by binned_error_bound().
#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "kernels/stats/distribution.hpp"
#include "kernels/stats/grid.hpp"
#include "platform/core/defaults.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::stats {

/// Kernels beyond |y − t|/h > kKdeCutoff are skipped: exp(−kKdeCutoff²/2) < 1e-17.
inline constexpr double kKdeCutoff = 8.9;

/// How Kde::pdf evaluates.
enum class KdeMethod {
  Auto,    ///< exact unless N·M > 2e7 and N > 2000, then binned with the default tolerance
  Exact,   ///< exact sums (to the cutoff above)
  Binned,  ///< linear binning, error bound binned_error_bound()
};

struct KdeOptions {
  KdeMethod method = KdeMethod::Auto;
  /// Target absolute error of the binned path, relative to the kernel peak 1/(h√(2π)):
  /// the bin width is chosen so that binned_error_bound() <= tol · φ(0)/h.
  double binned_tol = 1e-6;
  /// Worker threads for large evaluations (results identical for any count).
  int threads = kDefaultThreads;
};

/// Exact Gaussian KDE density of `data` (any order) with bandwidth h at the points x.
Eigen::VectorXd kde_pdf(ConstVec data, double h, ConstVec x, int threads = kDefaultThreads);
/// Exact Gaussian KDE CDF at x.
Eigen::VectorXd kde_cdf(ConstVec data, double h, ConstVec x, int threads = kDefaultThreads);
/// Binned Gaussian KDE density at x with bins of width `bin` (linear binning). Absolute error
/// <= binned_error_bound(h, bin).
Eigen::VectorXd kde_pdf_binned(ConstVec data, double h, ConstVec x, double bin, int threads = kDefaultThreads);
/// Bound on |binned − exact| density for bin width δ: δ² φ(0) / (8 h³) (the second derivative
/// of the kernel in t is at most φ(0)/h³; linear interpolation error is δ²/8 times that).
double binned_error_bound(double h, double bin);
/// KDE density on a §0 grid (the form screening, PR and calibration use): exact sums.
Eigen::VectorXd kde_pdf_grid(ConstVec data, double h, const Grid& g, int threads = kDefaultThreads);
/// KDE density on a grid by opt.method: Auto takes the binned path on the same rule as Kde::pdf
/// (N > 2000 and N·M > 2e7), with absolute error <= binned_error_bound(h, kde_bin_width(h, opt)).
Eigen::VectorXd kde_pdf_grid(ConstVec data, double h, const Grid& g, const KdeOptions& opt);
/// Whether opt.method selects the binned path for n_data points evaluated at n_points.
bool kde_uses_binned(Eigen::Index n_data, Eigen::Index n_points, const KdeOptions& opt);
/// Bin width meeting opt.binned_tol: h sqrt(8 tol), so that the bound is tol · φ(0)/h.
double kde_bin_width(double h, const KdeOptions& opt);

class Kde : public Distribution {
 public:
  /// Data must be finite, at least 1 point; h > 0 finite. Throws InvalidArgument otherwise.
  Kde(Eigen::VectorXd data, double h, KdeOptions opt = {});

  std::string describe() const override;
  std::string family() const override { return "kde"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  /// Inverse CDF by safeguarded Newton (bracketed by the data range ± 10h); below p = 1e-3 by
  /// bisection on logcdf (relative accuracy down to p = 1e-300).
  double quantile(double p) const override;
  // The tails in log space or by complements: each kernel's own tail, summed by
  // log-sum-exp, so the values keep their relative accuracy far from the data (exact sums, O(N)).
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  /// Σ Φ(−t_i)/N: the kernels' complements, not 1 − cdf.
  double sf(double x) const override;
  /// x with sf(x) = q: bisection on log sf for q < 1e-3, else quantile(1 − q).
  double isf(double q) const override;
  double mean() const override { return mean_; }
  /// sqrt(biased data variance + h²): the exact std of the KDE mixture.
  double stddev() const override;
  std::pair<double, double> support() const override;

  Eigen::VectorXd pdf(const Eigen::VectorXd& x) const override;
  Eigen::VectorXd cdf(const Eigen::VectorXd& x) const override;
  Eigen::VectorXd quantile(const Eigen::VectorXd& p) const override;
  /// Smoothed bootstrap: a data point at random plus h·z (z standard normal).
  Eigen::VectorXd sample(Rng& rng, Eigen::Index n) const override;
  /// "bandwidth", "n", "error_bound" (0 for the exact path).
  std::optional<double> field(std::string_view name) const override;

  double bandwidth() const { return h_; }
  /// Sorted data.
  const Eigen::VectorXd& data() const { return t_; }
  const KdeOptions& options() const { return opt_; }
  /// Tag used by describe(), e.g. the rule name ("silverman") or "kde_ebd".
  void set_label(std::string label) { label_ = std::move(label); }
  /// Adds a named numeric field reported by field() (KDE-ebd: "lower", "upper", "added").
  void set_field(std::string name, double value) { extra_.emplace_back(std::move(name), value); }

 private:
  Eigen::VectorXd t_;  // sorted
  double h_;
  KdeOptions opt_;
  double mean_ = 0.0, var_ = 0.0;
  std::string label_;
  std::vector<std::pair<std::string, double>> extra_;
};

/// Builds a KDE with a rule name ("silverman", "scott", "lscv", ...) or a fixed h.
std::shared_ptr<Kde> make_kde(const Eigen::VectorXd& data, const std::string& rule, KdeOptions opt = {});
std::shared_ptr<Kde> make_kde(const Eigen::VectorXd& data, double h, KdeOptions opt = {});

}  // namespace smi::stats
