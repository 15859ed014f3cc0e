// SPDX-License-Identifier: MIT
// Optimized Latin hypercubes: a random LHS improved by the enhanced stochastic evolutionary
// search (ESE) of Jin, Chen & Sudjianto (2005) on the phi_p criterion. Every move swaps two
// entries of one column, so the Latin property holds throughout; only the two touched rows'
// distances change, so a move costs O(n d) instead of O(n^2 d).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/surrogate/doe.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::surrogate::doe {
namespace {

/// d^-p from a squared distance, exact for the even integer exponents used by default.
struct InversePower {
  double p;
  int half = -1;  // p/2 when p is an even integer
  explicit InversePower(double pp) : p(pp) {
    if (pp == std::floor(pp) && static_cast<long>(pp) % 2 == 0 && pp <= 200) half = static_cast<int>(pp / 2);
  }
  double operator()(double d2) const {
    if (half < 0) return std::pow(d2, -p / 2);
    double base = 1.0 / d2, r = 1.0;
    for (int e = half; e; e >>= 1, base *= base)
      if (e & 1) r *= base;
    return r;
  }
};

class EseState {
 public:
  EseState(Eigen::MatrixXd X, double p) : X_(std::move(X)), pw_(p), n_(X_.rows()) {
    D2_.resize(n_, n_);
    recompute();
  }
  void recompute() {
    sum_ = 0;
    for (Eigen::Index i = 0; i < n_; ++i) {
      D2_(i, i) = 0;
      for (Eigen::Index j = i + 1; j < n_; ++j) {
        D2_(i, j) = D2_(j, i) = (X_.row(i) - X_.row(j)).squaredNorm();
        sum_ += pw_(D2_(i, j));
      }
    }
  }
  double phi() const { return std::pow(sum_, 1.0 / pw_.p); }
  double sum() const { return sum_; }
  /// Change of sum if X(a,k) and X(b,k) were swapped.
  double delta(Eigen::Index a, Eigen::Index b, Eigen::Index k) const {
    const double xa = X_(a, k), xb = X_(b, k);
    double ds = 0;
    for (Eigen::Index j = 0; j < n_; ++j) {
      if (j == a || j == b) continue;
      const double xj = X_(j, k);
      const double da = D2_(a, j) - (xa - xj) * (xa - xj) + (xb - xj) * (xb - xj);
      const double db = D2_(b, j) - (xb - xj) * (xb - xj) + (xa - xj) * (xa - xj);
      ds += pw_(da) - pw_(D2_(a, j)) + pw_(db) - pw_(D2_(b, j));
    }
    return ds;
  }
  void swap(Eigen::Index a, Eigen::Index b, Eigen::Index k, double ds) {
    const double xa = X_(a, k), xb = X_(b, k);
    for (Eigen::Index j = 0; j < n_; ++j) {
      if (j == a || j == b) continue;
      const double xj = X_(j, k);
      D2_(a, j) = D2_(j, a) = D2_(a, j) - (xa - xj) * (xa - xj) + (xb - xj) * (xb - xj);
      D2_(b, j) = D2_(j, b) = D2_(b, j) - (xb - xj) * (xb - xj) + (xa - xj) * (xa - xj);
    }
    std::swap(X_(a, k), X_(b, k));
    sum_ += ds;
  }
  const Eigen::MatrixXd& X() const { return X_; }

 private:
  Eigen::MatrixXd X_;
  InversePower pw_;
  Eigen::Index n_;
  Eigen::MatrixXd D2_;
  double sum_ = 0;
};

Eigen::MatrixXd random_lhs(Eigen::Index n, Eigen::Index d, Rng& rng, bool centered) {
  Eigen::MatrixXd X(n, d);
  std::vector<Eigen::Index> perm(n);
  for (Eigen::Index k = 0; k < d; ++k) {
    for (Eigen::Index i = 0; i < n; ++i) perm[i] = i;
    for (Eigen::Index i = n - 1; i > 0; --i) std::swap(perm[i], perm[rng.integer(0, i)]);  // Fisher-Yates
    for (Eigen::Index i = 0; i < n; ++i)
      X(i, k) = (static_cast<double>(perm[i]) + (centered ? 0.5 : rng.uniform01())) / static_cast<double>(n);
  }
  return X;
}

}  // namespace

Eigen::MatrixXd lhs(Eigen::Index n, Eigen::Index d, std::uint64_t seed, const LhsOptions& opt,
                    const cancel::Token& stop) {
  if (n < 1) throw InvalidArgument("lhs: need at least 1 point, got " + std::to_string(n));
  if (d < 1) throw InvalidArgument("lhs: need at least 1 dimension, got " + std::to_string(d));
  double p = opt.p;
  if (opt.criterion == "maximin")
    p = 50;
  else if (opt.criterion != "phip" && opt.criterion != "none")
    throw InvalidArgument("lhs: unknown criterion '" + opt.criterion + "' (use \"maximin\", \"phip\" or \"none\")");
  if (!(p >= kMinPhiP && p <= kMaxPhiP)) throw InvalidArgument(fmt::format("lhs: p must be in [{}, {}], got {}", kMinPhiP, kMaxPhiP, p));
  Rng rng(seed, hash_label("smi.doe.lhs"));
  Eigen::MatrixXd X0 = random_lhs(n, d, rng, opt.centered);
  if (opt.criterion == "none" || n < 3) return X0;

  // ESE parameters (Jin et al. 2005): J candidate swaps per step, M steps per outer iteration.
  const double ne = 0.5 * static_cast<double>(n) * static_cast<double>(n - 1);
  const int J = static_cast<int>(std::clamp(ne / 5.0, 2.0, 50.0));
  const int M = static_cast<int>(std::clamp(2.0 * ne * static_cast<double>(d) / J, 1.0, 100.0));
  int outer = opt.iterations;
  if (outer <= 0)  // bounded work: about 2e8 distance updates in all
    outer = static_cast<int>(std::clamp(2e8 / (double(M) * J * double(n) * double(d)), 2.0, 30.0));

  EseState st(std::move(X0), p);
  Eigen::MatrixXd best = st.X();
  double best_phi = st.phi();
  double T = 0.005 * best_phi;
  for (int it = 0; it < outer; ++it) {
    const double phi_old_best = best_phi;
    int accepted = 0, improved = 0;
    for (int step = 0; step < M; ++step) {
      stop.poll();  // a step updates J x n distances: well under a millisecond
      const Eigen::Index k = step % d;
      double best_ds = std::numeric_limits<double>::infinity();
      Eigen::Index ba = 0, bb = 1;
      for (int c = 0; c < J; ++c) {
        const Eigen::Index a = rng.integer(0, n - 1);
        Eigen::Index b = rng.integer(0, n - 2);
        if (b >= a) ++b;
        const double ds = st.delta(a, b, k);
        if (ds < best_ds) best_ds = ds, ba = a, bb = b;
      }
      const double phi_now = st.phi();
      const double phi_try = std::pow(std::max(st.sum() + best_ds, 0.0), 1.0 / p);
      if (phi_try - phi_now <= T * rng.uniform01()) {
        st.swap(ba, bb, k, best_ds);
        ++accepted;
        if (phi_try < best_phi) {
          best = st.X();
          best_phi = phi_try;
          ++improved;
        }
      }
    }
    st.recompute();  // wash out round-off of the incremental sums
    // Threshold control: exploit while improving, otherwise explore (heat up, then cool).
    const double acc = static_cast<double>(accepted) / M;
    if (best_phi < phi_old_best - 1e-12 * phi_old_best) {
      if (acc > 0.1 && improved < accepted) T *= 0.8;
      else if (acc <= 0.1) T /= 0.8;
    } else {
      if (acc < 0.1) T /= 0.7;
      else if (acc > 0.8) T *= 0.9;
    }
  }
  return best;
}

double phi_p(const Eigen::MatrixXd& X, double p) {
  InversePower pw(p);
  double s = 0;
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index j = i + 1; j < X.rows(); ++j) {
      const double d2 = (X.row(i) - X.row(j)).squaredNorm();
      if (d2 == 0) throw InvalidArgument("phi_p: rows " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " coincide");
      s += pw(d2);
    }
  return std::pow(s, 1.0 / p);
}

double min_distance(const Eigen::MatrixXd& X) {
  double m = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index j = i + 1; j < X.rows(); ++j) m = std::min(m, (X.row(i) - X.row(j)).squaredNorm());
  return std::sqrt(m);
}

Eigen::MatrixXd scale_to_bounds(const Eigen::MatrixXd& U, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  if (lo.size() != U.cols() || hi.size() != U.cols())
    throw DimensionMismatch("scale_to_bounds: " + std::to_string(U.cols()) + " columns but " + std::to_string(lo.size()) + " bounds");
  Eigen::MatrixXd X(U.rows(), U.cols());
  for (Eigen::Index k = 0; k < U.cols(); ++k) X.col(k) = lo[k] + (hi[k] - lo[k]) * U.col(k).array();
  return X;
}

Eigen::MatrixXd full_factorial(const std::vector<Eigen::VectorXd>& levels) {
  if (levels.empty()) throw InvalidArgument("full_factorial: need at least one factor");
  Eigen::Index total = 1;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if (levels[k].size() < 1) throw InvalidArgument("full_factorial: factor " + std::to_string(k + 1) + " has no levels");
    total *= levels[k].size();
    if (total > (Eigen::Index(1) << 26)) throw InvalidArgument("full_factorial: more than 2^26 points; use lhs or sobol");
  }
  const Eigen::Index d = static_cast<Eigen::Index>(levels.size());
  Eigen::MatrixXd X(total, d);
  Eigen::Index stride = total;
  for (Eigen::Index k = 0; k < d; ++k) {
    const Eigen::Index L = levels[k].size();
    stride /= L;
    for (Eigen::Index i = 0; i < total; ++i) X(i, k) = levels[k][(i / stride) % L];
  }
  return X;
}

}  // namespace smi::surrogate::doe
