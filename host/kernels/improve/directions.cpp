// SPDX-License-Identifier: MIT
#include "kernels/improve/directions.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "platform/core/errors.hpp"

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

/// The directions (columns of V, strongest first) with their curvatures; from the summaries'
/// Jacobian also its left vectors U, singular values sv and the summaries S0 at the optimum.
struct Basis {
  Eigen::MatrixXd V, U;
  Eigen::VectorXd sv, curv, S0;
  double smax = 0.0;
};

/// Basis from the SVD of the summaries' Jacobian by central differences around c (2k + 1 runs).
Basis summaries_basis(Scaled& s, const Summaries& summaries, const Eigen::VectorXd& u0, const Eigen::VectorXd& c, double h) {
  const Eigen::Index k = u0.size();
  Basis b;
  b.S0 = summaries(s.theta(u0));
  Eigen::MatrixXd J(b.S0.size(), k);
  for (Eigen::Index i = 0; i < k; ++i) {
    Eigen::VectorXd up = c, dn = c;
    up[i] += h;
    dn[i] -= h;
    J.col(i) = (summaries(s.theta(up)) - summaries(s.theta(dn))) / (2.0 * h);
  }
  s.evaluations += static_cast<int>(2 * k + 1);
  if (!J.allFinite()) throw Error("identifiability: the summaries' Jacobian at the optimum is not finite");
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  b.V = svd.matrixV();
  b.U = svd.matrixU();
  b.sv = Eigen::VectorXd::Zero(k);
  b.sv.head(svd.singularValues().size()) = svd.singularValues();  // descending; zeros past the rank
  b.curv = b.sv.array().square();
  b.smax = b.sv[0];
  return b;
}

/// Basis from the eigenvectors of the objective's Hessian around c.
Basis hessian_basis(Scaled& s, const Eigen::VectorXd& c, double h) {
  const Eigen::Index k = c.size();
  Basis b;
  b.V.resize(k, k);
  b.curv.resize(k);
  const Eigen::MatrixXd H = scaled_hessian(s, c, h);
  if (!H.allFinite()) throw Error("identifiability: the objective's Hessian at the optimum is not finite");
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
  for (Eigen::Index j = 0; j < k; ++j) {  // ascending -> descending
    b.V.col(j) = es.eigenvectors().col(k - 1 - j);
    b.curv[j] = es.eigenvalues()[k - 1 - j];
  }
  return b;
}

/// Walks the directions of a basis from the optimum u0 (scaled units), profiling the objective.
struct Walker {
  Scaled& s;
  const Summaries& summaries;
  const DirectionsOptions& opt;
  const Basis& b;
  const Eigen::VectorXd& u0;
  double value;  // the objective at the optimum

  /// The point at distance t along direction d, corrected along the stronger directions (the
  /// pseudo-inverse of the Jacobian restricted to them) to keep the summaries at the optimum's.
  /// Weaker directions are left alone: dividing by their near-zero singular values would throw
  /// the point across the box on noise.
  Eigen::VectorXd node(Eigen::Index d, double t) {
    const Eigen::Index k = u0.size();
    Eigen::VectorXd u = (u0 + t * b.V.col(d)).cwiseMax(0.0).cwiseMin(1.0);
    if (!summaries) return u;
    for (int it = 0; it < opt.corrections; ++it) {
      const Eigen::VectorXd dS = summaries(s.theta(u)) - b.S0;
      ++s.evaluations;
      Eigen::VectorXd step = Eigen::VectorXd::Zero(k);
      for (Eigen::Index j = 0; j < std::min<Eigen::Index>(k, b.U.cols()); ++j)
        if (j < d && b.sv[j] > 1e-3 * b.smax) step -= b.V.col(j) * (b.U.col(j).dot(dS) / b.sv[j]);
      u = (u + step).cwiseMax(0.0).cwiseMin(1.0);
    }
    return u;
  }

  /// One side of direction d, out to `end` in `side` steps: the profile nodes go to prof; stops
  /// once the rise passes the tolerance and bisects that crossing. Returns whether it crossed;
  /// ok_t, ok_u: the farthest point still within the tolerance.
  bool walk_side(Direction& dir, Eigen::Index d, double sign, double end, int side,
                 std::vector<std::pair<double, double>>& prof, double& ok_t, Eigen::VectorXd& ok_u) {
    double ok = 0.0, bad = 0.0;
    bool crossed = false;
    ok_u = u0;
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
    ok_t = ok;
    return crossed;
  }

  /// Direction d: its loadings (largest positive), curvature, reach to the box and profile.
  /// Walks out from the optimum towards each bound; a side stops once the rise passes the
  /// tolerance (a determined direction needs no profile to its bounds). The farthest
  /// within-tolerance point of each side goes to near.
  Direction profile(Eigen::Index d, std::vector<std::pair<Eigen::VectorXd, Eigen::Index>>& near) {
    Direction dir;
    dir.loadings = b.V.col(d);
    Eigen::Index big = 0;
    dir.loadings.cwiseAbs().maxCoeff(&big);
    const double sign = dir.loadings[big] < 0 ? -1.0 : 1.0;
    dir.loadings *= sign;
    dir.curvature = b.curv[d];
    std::tie(dir.t_lower, dir.t_upper) = reach(u0, dir.loadings);
    const int side = std::max(1, (opt.points - 1) / 2);
    std::vector<std::pair<double, double>> prof{{0.0, value}};
    bool determined = true;  // bounded on both sides: by a rise past the tolerance, or by the box at the optimum
    for (double end : {dir.t_lower, dir.t_upper}) {
      if (std::abs(end) < 1e-9) continue;
      double ok = 0.0;
      Eigen::VectorXd ok_u;
      determined = walk_side(dir, d, sign, end, side, prof, ok, ok_u) && determined;
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
    return dir;
  }
};

void check_directions_input(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum, const DirectionsOptions& opt) {
  validate_parameters(params);
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  if (optimum.size() != k) throw DimensionMismatch(fmt::format("optimum has {} values for {} parameters", optimum.size(), k));
  if (!(opt.tolerance > 0.0) || !std::isfinite(opt.tolerance))
    throw InvalidArgument(fmt::format("identifiability tolerance must be a number > 0, got {}", opt.tolerance));
  if (opt.points < 3) throw InvalidArgument(fmt::format("identifiability needs >= 3 profile points, got {}", opt.points));
  if (!(opt.step > 0.0 && opt.step <= kMaxDirectionsStep))
    throw InvalidArgument(fmt::format("identifiability step must be in (0, {}], got {}", kMaxDirectionsStep, opt.step));
}

/// The warning when some directions are not determined, naming the weakest by its loadings.
void warn_undetermined(const std::vector<Parameter>& params, const DirectionsOptions& opt, DirectionsResult& r) {
  int weak = 0;
  for (const Direction& d : r.directions) weak += !d.determined;
  if (weak == 0) return;
  const Direction& d = r.directions.back();
  std::string load;
  for (Eigen::Index i = 0; i < d.loadings.size(); ++i)
    if (std::abs(d.loadings[i]) >= 0.1)
      load += fmt::format("{}{:+.3f} {}", load.empty() ? "" : " ", d.loadings[i], params[static_cast<std::size_t>(i)].name);
  r.warnings.push_back(fmt::format("{} of {} parameter directions are not determined by the data (the objective rises by less than {:.3g} "
                                   "along them to a bound on at least one side); the weakest: {} (scaled units). See identifiability.directions "
                                   "and near_optimal",
                                   weak, params.size(), opt.tolerance, load));
}

}  // namespace

DirectionsResult identifiability_directions(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum,
                                            double value, const DirectionsOptions& opt, const Summaries& summaries) {
  check_directions_input(params, optimum, opt);
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
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
  r.basis = summaries ? "summaries" : "hessian";
  const Basis b = summaries ? summaries_basis(s, summaries, u0, c, h) : hessian_basis(s, c, h);

  Walker walker{s, summaries, opt, b, u0, value};
  std::vector<std::pair<Eigen::VectorXd, Eigen::Index>> near;
  for (Eigen::Index d = 0; d < k; ++d) r.directions.push_back(walker.profile(d, near));

  // Near-optimal set: the optimum, then the far points of every undetermined direction.
  r.near_optimal.push_back(optimum);
  r.near_optimal_values.push_back(value);
  for (const auto& [u, d] : near) {
    if (r.directions[static_cast<std::size_t>(d)].determined) continue;
    r.near_optimal.push_back(s.theta(u));
    r.near_optimal_values.push_back(s(u));
  }
  warn_undetermined(params, opt, r);
  r.evaluations = s.evaluations;
  return r;
}

}  // namespace smi::improve
