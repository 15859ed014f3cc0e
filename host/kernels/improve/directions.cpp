#include "kernels/improve/directions.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "kernels/core/errors.hpp"

namespace smi::improve {

namespace {

/// Maps scaled u to θ (clamped to the box) and counts evaluations.
struct Scaled {
  const std::vector<Parameter>& params;
  const Objective& f;
  int evaluations = 0;

  Eigen::VectorXd theta(const Eigen::VectorXd& u) const {
    Eigen::VectorXd t(u.size());
    for (Eigen::Index i = 0; i < u.size(); ++i) {
      const Parameter& p = params[static_cast<std::size_t>(i)];
      t[i] = p.lower + std::clamp(u[i], 0.0, 1.0) * (p.upper - p.lower);
    }
    return t;
  }
  double operator()(const Eigen::VectorXd& u) {
    ++evaluations;
    return f(theta(u)).value;
  }
};

/// Distance along v from u to the box [0, 1]^k on each side.
std::pair<double, double> reach(const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    if (std::abs(v[i]) < 1e-14) continue;
    const double a = (0.0 - u[i]) / v[i], b = (1.0 - u[i]) / v[i];
    lo = std::max(lo, std::min(a, b));
    hi = std::min(hi, std::max(a, b));
  }
  return {std::min(0.0, lo), std::max(0.0, hi)};
}

/// Hessian of f in scaled units by central differences around c (1 + 2k² evaluations).
Eigen::MatrixXd scaled_hessian(Scaled& s, const Eigen::VectorXd& c, double h) {
  const Eigen::Index k = c.size();
  Eigen::MatrixXd H(k, k);
  const double f0 = s(c);
  for (Eigen::Index i = 0; i < k; ++i) {
    Eigen::VectorXd u = c;
    u[i] = c[i] + h;
    const double fp = s(u);
    u[i] = c[i] - h;
    const double fm = s(u);
    H(i, i) = (fp - 2.0 * f0 + fm) / (h * h);
  }
  for (Eigen::Index i = 0; i < k; ++i)
    for (Eigen::Index j = i + 1; j < k; ++j) {
      Eigen::VectorXd u = c;
      double acc = 0.0;
      for (int a : {1, -1})
        for (int b : {1, -1}) {
          u[i] = c[i] + a * h;
          u[j] = c[j] + b * h;
          acc += a * b * s(u);
        }
      H(i, j) = H(j, i) = acc / (4.0 * h * h);
    }
  return H;
}

}  // namespace

DirectionsResult identifiability_directions(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum,
                                            double value, const DirectionsOptions& opt, const Summaries& summaries) {
  validate_parameters(params);
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  if (optimum.size() != k) throw DimensionMismatch(fmt::format("optimum has {} values for {} parameters", optimum.size(), k));
  if (!(opt.tolerance > 0.0) || !std::isfinite(opt.tolerance))
    throw InvalidArgument(fmt::format("identifiability tolerance must be a number > 0, got {}", opt.tolerance));
  if (opt.points < 3) throw InvalidArgument(fmt::format("identifiability needs >= 3 profile points, got {}", opt.points));
  if (!(opt.step > 0.0 && opt.step <= 0.05)) throw InvalidArgument(fmt::format("identifiability step must be in (0, 0.05], got {}", opt.step));
  Scaled s{params, f};
  Eigen::VectorXd u0(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Parameter& p = params[static_cast<std::size_t>(i)];
    u0[i] = std::clamp((optimum[i] - p.lower) / (p.upper - p.lower), 0.0, 1.0);
  }
  DirectionsResult r;
  r.tolerance = opt.tolerance;
  // Difference stencils are centred inside the box: the objective need not exist outside it
  // (a std below 0, a lognormal mean at 0).
  const double h = opt.step;
  const Eigen::VectorXd c = u0.cwiseMax(h).cwiseMin(1.0 - h);

  Eigen::MatrixXd V(k, k), U;  // directions (columns, strongest first); summaries' left vectors
  Eigen::VectorXd sv(k), curv(k), S0;
  if (summaries) {
    r.basis = "summaries";
    S0 = summaries(s.theta(u0));
    Eigen::MatrixXd J(S0.size(), k);
    for (Eigen::Index i = 0; i < k; ++i) {
      Eigen::VectorXd up = c, dn = c;
      up[i] += h;
      dn[i] -= h;
      J.col(i) = (summaries(s.theta(up)) - summaries(s.theta(dn))) / (2.0 * h);
    }
    s.evaluations += static_cast<int>(2 * k + 1);
    if (!J.allFinite()) throw Error("identifiability: the summaries' Jacobian at the optimum is not finite");
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
    V = svd.matrixV();
    U = svd.matrixU();
    sv.setZero();
    sv.head(svd.singularValues().size()) = svd.singularValues();  // descending; zeros past the rank
    curv = sv.array().square();
  } else {
    r.basis = "hessian";
    const Eigen::MatrixXd H = scaled_hessian(s, c, h);
    if (!H.allFinite()) throw Error("identifiability: the objective's Hessian at the optimum is not finite");
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
    for (Eigen::Index j = 0; j < k; ++j) {  // ascending -> descending
      V.col(j) = es.eigenvectors().col(k - 1 - j);
      curv[j] = es.eigenvalues()[k - 1 - j];
    }
  }
  const double smax = summaries ? sv[0] : 0.0;

  // The point at distance t along direction d, corrected along the stronger directions (the
  // pseudo-inverse of the Jacobian restricted to them) to keep the summaries at the optimum's.
  // Weaker directions are left alone: dividing by their near-zero singular values would throw
  // the point across the box on noise.
  auto node = [&](Eigen::Index d, double t) -> Eigen::VectorXd {
    Eigen::VectorXd u = (u0 + t * V.col(d)).cwiseMax(0.0).cwiseMin(1.0);
    if (!summaries) return u;
    for (int it = 0; it < opt.corrections; ++it) {
      const Eigen::VectorXd dS = summaries(s.theta(u)) - S0;
      ++s.evaluations;
      Eigen::VectorXd step = Eigen::VectorXd::Zero(k);
      for (Eigen::Index j = 0; j < std::min<Eigen::Index>(k, U.cols()); ++j)
        if (j < d && sv[j] > 1e-3 * smax) step -= V.col(j) * (U.col(j).dot(dS) / sv[j]);
      u = (u + step).cwiseMax(0.0).cwiseMin(1.0);
    }
    return u;
  };

  const int side = std::max(1, (opt.points - 1) / 2);
  std::vector<std::pair<Eigen::VectorXd, Eigen::Index>> near;
  for (Eigen::Index d = 0; d < k; ++d) {
    Direction dir;
    dir.loadings = V.col(d);
    Eigen::Index big = 0;
    dir.loadings.cwiseAbs().maxCoeff(&big);
    const double sign = dir.loadings[big] < 0 ? -1.0 : 1.0;
    dir.loadings *= sign;
    dir.curvature = curv[d];
    std::tie(dir.t_lower, dir.t_upper) = reach(u0, dir.loadings);
    // Walk out from the optimum towards each bound; stop a side once the rise passes the
    // tolerance (a determined direction needs no profile to its bounds).
    std::vector<std::pair<double, double>> prof{{0.0, value}};
    bool determined = true;  // bounded on both sides: by a rise past the tolerance, or by the box at the optimum
    for (double end : {dir.t_lower, dir.t_upper}) {
      if (std::abs(end) < 1e-9) continue;
      double ok = 0.0, bad = 0.0;
      bool crossed = false;
      Eigen::VectorXd ok_u = u0;
      for (int j = 1; j <= side; ++j) {
        const double t = end * j / side;
        const Eigen::VectorXd u = node(d, sign * t);
        const double v = s(u);
        prof.emplace_back(t, v);
        dir.rise = std::max(dir.rise, v - value);
        if (v - value > opt.tolerance) {
          bad = t;
          crossed = true;
          break;
        }
        ok = t;
        ok_u = u;
      }
      determined = determined && crossed;
      if (crossed)  // bisect the crossing for the near-optimal set
        for (int it = 0; it < 5; ++it) {
          const double t = 0.5 * (ok + bad);
          const Eigen::VectorXd u = node(d, sign * t);
          if (s(u) - value <= opt.tolerance) {
            ok = t;
            ok_u = u;
          } else {
            bad = t;
          }
        }
      if (ok != 0.0) near.emplace_back(ok_u, d);
    }
    dir.determined = determined;
    std::sort(prof.begin(), prof.end());
    dir.t.resize(static_cast<Eigen::Index>(prof.size()));
    dir.profile.resize(dir.t.size());
    for (std::size_t j = 0; j < prof.size(); ++j) {
      dir.t[static_cast<Eigen::Index>(j)] = prof[j].first;
      dir.profile[static_cast<Eigen::Index>(j)] = prof[j].second;
    }
    r.directions.push_back(std::move(dir));
  }

  // Near-optimal set: the optimum, then the far points of every undetermined direction.
  r.near_optimal.push_back(optimum);
  r.near_optimal_values.push_back(value);
  for (const auto& [u, d] : near) {
    if (r.directions[static_cast<std::size_t>(d)].determined) continue;
    r.near_optimal.push_back(s.theta(u));
    r.near_optimal_values.push_back(s(u));
  }
  int weak = 0;
  for (const Direction& d : r.directions) weak += !d.determined;
  if (weak > 0) {
    const Direction& d = r.directions.back();
    std::string load;
    for (Eigen::Index i = 0; i < k; ++i)
      if (std::abs(d.loadings[i]) >= 0.1)
        load += fmt::format("{}{:+.3f} {}", load.empty() ? "" : " ", d.loadings[i], params[static_cast<std::size_t>(i)].name);
    r.warnings.push_back(fmt::format("{} of {} parameter directions are not determined by the data (the objective rises by less than {:.3g} "
                                     "along them to a bound on at least one side); the weakest: {} (scaled units). See identifiability.directions "
                                     "and near_optimal",
                                     weak, k, opt.tolerance, load));
  }
  r.evaluations = s.evaluations;
  return r;
}

}  // namespace smi::improve
