// SPDX-License-Identifier: MIT
// smi::kriging::fit: checks and normalisation, the theta search (given / boxmin / ML), and the
// final factorisation with a diagnosis when R is numerically singular.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

#include "kernels/surrogate/boxmin.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "kernels/surrogate/likelihood.hpp"
#include "kernels/surrogate/ml_search.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::surrogate::kriging {
namespace {

constexpr Eigen::Index kSubsetAbove = 400, kSubset = 250;

std::string vec_text(const Eigen::VectorXd& v) {
  std::ostringstream os;
  os.precision(4);
  os << "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) os << (i ? ", " : "") << v[i];
  os << ")";
  return os.str();
}

/// Length-1 vectors expand to n (DACE's isotropic shorthand); other lengths must be n.
Eigen::VectorXd expand(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() == n) return v;
  if (v.size() == 1) return Eigen::VectorXd::Constant(n, v[0]);
  throw DimensionMismatch(std::string(what) + " has " + std::to_string(v.size()) + " values, need 1 or " +
                          std::to_string(n) + " (one per input)");
}

/// Rows that coincide (after normalisation): the classic cause of a singular R.
std::pair<Eigen::Index, Eigen::Index> find_duplicate(const Eigen::MatrixXd& S) {
  std::vector<Eigen::Index> idx(S.rows());
  std::iota(idx.begin(), idx.end(), 0);
  auto less = [&](Eigen::Index a, Eigen::Index b) {
    for (Eigen::Index j = 0; j < S.cols(); ++j)
      if (S(a, j) != S(b, j)) return S(a, j) < S(b, j);
    return a < b;
  };
  std::sort(idx.begin(), idx.end(), less);
  for (std::size_t k = 1; k < idx.size(); ++k)
    if (S.row(idx[k]) == S.row(idx[k - 1])) return {std::min(idx[k], idx[k - 1]), std::max(idx[k], idx[k - 1])};
  return {-1, -1};
}

std::string singular_diagnosis(const detail::Problem& pb, const Eigen::VectorXd& theta, const detail::Factors& f) {
  // The most correlated pair (smallest weighted distance s) is what breaks the factorisation.
  Eigen::VectorXd s = pb.D * theta;
  Eigen::Index k = 0;
  s.minCoeff(&k);
  Eigen::Index j = 0, kk = k, m = pb.m();
  while (kk >= m - 1 - j) kk -= m - 1 - j, ++j;
  const Eigen::Index i = j + 1 + kk;
  Eigen::ArrayXd r = s.array().segment(k, 1);
  corr_from_s(pb.corr, r);
  (void)f;
  std::ostringstream os;
  os << "the correlation matrix is numerically singular at theta = " << vec_text(theta) << ": design rows " << j + 1
     << " and " << i + 1 << " have correlation " << std::setprecision(10) << r[0]
     << " (nearly duplicate points, or theta too small for this many points)";
  return os.str();
}

// Shapes agree, every value is finite and the design has points enough for the trend.
void check_fit_input(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const FitOptions& opt) {
  const Eigen::Index m = X.rows(), n = X.cols();
  if (m < 2) throw InvalidArgument("need at least 2 design points, got " + std::to_string(m));
  if (y.size() != m)
    throw DimensionMismatch("X has " + std::to_string(m) + " rows but y has " + std::to_string(y.size()) + " values");
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j)
      if (!std::isfinite(X(i, j)))
        throw InvalidArgument("X[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "] is not finite");
    if (!std::isfinite(y[i])) throw InvalidArgument("y[" + std::to_string(i + 1) + "] is not finite");
  }
  const Eigen::Index p = trend_size(opt.trend, n);
  if (p > m)
    throw InvalidArgument("the " + std::string(trend_name(opt.trend)) + " trend has " + std::to_string(p) +
                          " coefficients but there are only " + std::to_string(m) + " points; use a lower trend");
}

// The centring and scaling of inputs and response (md.mS, sS, mY, sY): means and standard
// deviations with opt.normalize, none (0 and 1) without.
void set_normalization(Model& md, const Eigen::MatrixXd& X, const Eigen::VectorXd& y, bool normalize) {
  const Eigen::Index m = X.rows(), n = X.cols();
  md.mS = X.colwise().mean();
  md.sS = Eigen::RowVectorXd::Ones(n);
  md.mY = 0, md.sY = 1;
  if (normalize) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const double sd = std::sqrt((X.col(j).array() - md.mS[j]).square().sum() / static_cast<double>(m - 1));
      md.sS[j] = sd > 0 ? sd : 1.0;
    }
    md.mY = y.mean();
    const double sdy = std::sqrt((y.array() - md.mY).square().sum() / static_cast<double>(m - 1));
    md.sY = sdy > 0 ? sdy : 1.0;
  } else {
    md.mS.setZero();
  }
}

// Identical design rows make R singular unless a nugget is given or estimated.
void check_nugget_and_duplicates(const Eigen::MatrixXd& S, const FitOptions& opt) {
  if (!opt.estimate_nugget && opt.nugget <= 0) {
    const auto [a, b] = find_duplicate(S);
    if (a >= 0)
      throw InvalidArgument("design rows " + std::to_string(a + 1) + " and " + std::to_string(b + 1) +
                            " are identical (multiple design sites are not allowed): average their responses, "
                            "or pass nugget = true to treat the response as noisy");
  }
  if (!(opt.nugget >= 0 && opt.nugget < 1)) throw InvalidArgument("nugget must be in [0, 1), got " + std::to_string(opt.nugget));
}

// theta given by the caller.
Eigen::VectorXd fixed_theta(const FitOptions& opt, Eigen::Index n, Model& md) {
  Eigen::VectorXd theta = expand(*opt.theta, n, "theta");
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(theta[j] > 0 && std::isfinite(theta[j])))
      throw InvalidArgument("theta[" + std::to_string(j + 1) + "] must be positive and finite, got " +
                            std::to_string(theta[j]));
  md.method = "fixed";
  return theta;
}

// theta by DACE's boxmin (pattern search on psi).
Eigen::VectorXd boxmin_theta(const detail::Problem& pb, const FitOptions& opt, Eigen::Index n, double nugget, Model& md) {
  const Eigen::VectorXd t0 = opt.theta0.size() ? expand(opt.theta0, n, "theta0") : Eigen::VectorXd::Constant(n, 10.0);
  const Eigen::VectorXd lo = opt.lower.size() ? expand(opt.lower, n, "lower") : Eigen::VectorXd::Constant(n, 0.1);
  const Eigen::VectorXd up = opt.upper.size() ? expand(opt.upper, n, "upper") : Eigen::VectorXd::Constant(n, 20.0);
  auto psi = [&](const Eigen::VectorXd& t) {
    const detail::Factors f = detail::factorize(pb, t, nugget);
    return f.ok ? f.psi : std::numeric_limits<double>::infinity();
  };
  const BoxminResult r = boxmin(t0, lo, up, psi);
  if (std::isinf(r.f))
    throw InvalidArgument("boxmin: bad parameter region at theta0 = " + vec_text(r.theta) + ", try increasing upper");
  md.method = "boxmin", md.evaluations = r.evaluations, md.lower = lo, md.upper = up;
  return r.theta;
}

// The maximum-likelihood search box. Bounds scaled to the design: tau = theta * range^2
// (range^1 for exp) between a nearly flat correlation over the whole range and no correlation
// between neighbours; the caller's lower/upper replace them.
void ml_bounds(const Eigen::MatrixXd& S, const FitOptions& opt, Eigen::VectorXd& lo, Eigen::VectorXd& up) {
  const Eigen::Index m = S.rows(), n = S.cols();
  lo.resize(n), up.resize(n);
  const bool sq = !uses_abs(opt.corr);
  const double dens = std::pow(static_cast<double>(m), (sq ? 2.0 : 1.0) / static_cast<double>(n));
  for (Eigen::Index j = 0; j < n; ++j) {
    double r = S.col(j).maxCoeff() - S.col(j).minCoeff();
    if (!(r > 0)) r = 1;
    const double scale = sq ? r * r : r;
    lo[j] = (sq ? 1e-6 : 1e-3) / scale;
    up[j] = 20.0 * std::max(1.0, dens) / scale;
  }
  if (opt.lower.size()) lo = expand(opt.lower, n, "lower");
  if (opt.upper.size()) up = expand(opt.upper, n, "upper");
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(lo[j] > 0 && lo[j] < up[j]))
      throw InvalidArgument("need 0 < lower < upper for theta[" + std::to_string(j + 1) + "]");
}

// Large designs: search on a random subset (the likelihood surface's shape is set by the
// spacing, which a subset of a space-filling design keeps roughly), then polish with L-BFGS on
// all points from there. Each full evaluation costs O(m^3).
detail::MlResult ml_search_on_subset(const detail::Problem& pb, const Eigen::MatrixXd& S, const Eigen::VectorXd& Y,
                                     const FitOptions& opt, const Eigen::VectorXd& lo, const Eigen::VectorXd& up,
                                     double nugget) {
  const Eigen::Index m = S.rows(), n = S.cols();
  Rng rng(opt.seed, hash_label("smi.kriging/subset"));
  std::vector<Eigen::Index> idx(m);
  std::iota(idx.begin(), idx.end(), 0);
  for (Eigen::Index i = 0; i < kSubset; ++i) std::swap(idx[i], idx[rng.integer(i, m - 1)]);
  Eigen::MatrixXd Ss(kSubset, n);
  Eigen::VectorXd Ys(kSubset);
  for (Eigen::Index i = 0; i < kSubset; ++i) Ss.row(i) = S.row(idx[i]), Ys[i] = Y[idx[i]];
  const detail::Problem sub(Ss, Ys, opt.trend, opt.corr);
  const detail::MlResult rs = detail::ml_search(sub, lo, up, nugget, opt.estimate_nugget, 0, opt.seed, opt.threads);
  detail::MlResult r = detail::ml_search(pb, lo, up, nugget, opt.estimate_nugget, 1, opt.seed, opt.threads, &rs, 40);
  r.evaluations += rs.evaluations;
  return r;
}

// A theta at a bound of the search box says something about the input: warn.
void warn_at_bounds(const Eigen::VectorXd& theta, const Eigen::VectorXd& lo, const Eigen::VectorXd& up, Model& md) {
  for (Eigen::Index j = 0; j < theta.size(); ++j) {
    if (theta[j] <= lo[j] * 1.0001)
      md.warnings.push_back("theta[" + std::to_string(j + 1) + "] is at its lower bound: input " +
                            std::to_string(j + 1) + " acts (almost) linearly or not at all; consider trend = \"linear\"");
    if (theta[j] >= up[j] * 0.9999)
      md.warnings.push_back("theta[" + std::to_string(j + 1) + "] is at its upper bound: the response looks "
                            "uncorrelated at this design's spacing in input " + std::to_string(j + 1) +
                            "; add points or a nugget");
  }
}

// theta (and the nugget, when estimated) by maximum likelihood.
Eigen::VectorXd ml_theta(const detail::Problem& pb, const Eigen::MatrixXd& S, const Eigen::VectorXd& Y,
                         const FitOptions& opt, double& nugget, Model& md) {
  Eigen::VectorXd lo, up;
  ml_bounds(S, opt, lo, up);
  const detail::MlResult r =
      S.rows() > kSubsetAbove && opt.starts == 0
          ? ml_search_on_subset(pb, S, Y, opt, lo, up, nugget)
          : detail::ml_search(pb, lo, up, nugget, opt.estimate_nugget, opt.starts, opt.seed, opt.threads);
  if (!std::isfinite(r.log_psi) || r.log_psi >= 1e9)
    throw InvalidArgument("no theta in the search box gives a positive definite correlation matrix; "
                          "pass nugget = true (noisy response) or remove near-duplicate points");
  nugget = r.nugget;
  md.method = "ml", md.evaluations = r.evaluations, md.lower = lo, md.upper = up;
  warn_at_bounds(r.theta, lo, up, md);
  return r.theta;
}

// Final factorisation. If R is singular at a given theta, add the smallest jitter that works
// (as OpenTURNS does) and say so; give up with the diagnosis beyond 1e-6.
void add_jitter_if_singular(const detail::Problem& pb, const Eigen::VectorXd& theta, double& nugget, Model& md) {
  detail::Factors f = detail::factorize(pb, theta, nugget);
  if (f.ok) return;
  const std::string why = singular_diagnosis(pb, theta, f);
  double jitter = 1e-12;
  for (; jitter <= 1e-6 && !f.ok; jitter *= 10) f = detail::factorize(pb, theta, nugget + jitter);
  if (!f.ok)
    throw InvalidArgument(why + "; fix: increase theta, pass nugget = 1e-6 (or true), or remove near-duplicate points");
  nugget += jitter / 10;
  md.warnings.push_back(why + "; added a nugget of " + std::to_string(jitter / 10) + " to factorise it");
}

}  // namespace



Model fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const FitOptions& opt) {
  check_fit_input(X, y, opt);
  const Eigen::Index n = X.cols();
  Model md;
  md.trend = opt.trend, md.corr = opt.corr;
  set_normalization(md, X, y, opt.normalize);
  Eigen::MatrixXd S = (X.rowwise() - md.mS).array().rowwise() / md.sS.array();
  Eigen::VectorXd Y = (y.array() - md.mY) / md.sY;
  check_nugget_and_duplicates(S, opt);

  const detail::Problem pb(S, Y, opt.trend, opt.corr);
  double nugget = opt.nugget;
  Eigen::VectorXd theta;
  if (opt.theta) theta = fixed_theta(opt, n, md);
  else if (opt.method == "boxmin") theta = boxmin_theta(pb, opt, n, nugget, md);
  else if (opt.method == "ml") theta = ml_theta(pb, S, Y, opt, nugget, md);
  else throw InvalidArgument("unknown method '" + opt.method + "' (use \"ml\" or \"boxmin\")");

  add_jitter_if_singular(pb, theta, nugget, md);
  md.S = std::move(S), md.Y = std::move(Y);
  return assemble(pb, theta, nugget, std::move(md));
}

Model assemble(const detail::Problem& pb, const Eigen::VectorXd& theta, double nugget, Model md) {
  detail::Factors f = detail::factorize(pb, theta, nugget);
  if (!f.ok) throw InvalidArgument("the correlation matrix is not positive definite at theta = " + vec_text(theta));
  md.theta = theta, md.nugget = nugget;
  md.C = std::move(f.C), md.Ft = std::move(f.Ft), md.Q = std::move(f.Q), md.G = std::move(f.G);
  md.beta = std::move(f.beta), md.gamma = std::move(f.gamma);
  md.sigma2 = f.sigma2, md.psi = f.psi;
  if (md.S.size() == 0) md.S = pb.S, md.Y = pb.Y;
  return md;
}

}  // namespace smi::surrogate::kriging
