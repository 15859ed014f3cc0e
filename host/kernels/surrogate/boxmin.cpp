// SPDX-License-Identifier: MIT
// boxmin: start, then kmax rounds of explore + move (spec §4 lists the comparisons).
#include "kernels/surrogate/boxmin.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "platform/core/errors.hpp"

namespace smi::surrogate::kriging {
namespace {

struct State {
  Eigen::VectorXd t, D, lo, up;
  std::vector<Eigen::Index> ne;  // components free to move (D != 1)
  double f = 0;
  int nv = 0;
};

void rotate_left_pow(Eigen::VectorXd& D, double e) {
  const Eigen::Index p = D.size();
  Eigen::VectorXd r(p);
  for (Eigen::Index i = 0; i < p; ++i) r[i] = std::pow(D[(i + 1) % p], e);
  D = r;
}

void explore(State& s, const std::function<double(const Eigen::VectorXd&)>& f) {
  for (Eigen::Index j : s.ne) {
    Eigen::VectorXd tt = s.t;
    const double DD = s.D[j];
    bool atbd = true;
    if (s.t[j] == s.up[j])
      tt[j] = s.t[j] / std::sqrt(DD);
    else if (s.t[j] == s.lo[j])
      tt[j] = s.t[j] * std::sqrt(DD);
    else {
      atbd = false;
      tt[j] = std::min(s.up[j], s.t[j] * DD);
    }
    double ff = f(tt);
    ++s.nv;
    if (ff < s.f) {
      s.t = tt, s.f = ff;
    } else if (!atbd) {  // try a decrease
      tt[j] = std::max(s.lo[j], s.t[j] / DD);
      ff = f(tt);
      ++s.nv;
      if (ff < s.f) s.t = tt, s.f = ff;
    }
  }
}

void move(const Eigen::VectorXd& th, State& s, const std::function<double(const Eigen::VectorXd&)>& f) {
  Eigen::VectorXd v = s.t.cwiseQuotient(th);
  if ((v.array() == 1.0).all()) {
    rotate_left_pow(s.D, 0.2);
    return;
  }
  for (bool rept = true; rept;) {
    const Eigen::VectorXd tt = s.t.cwiseProduct(v).cwiseMax(s.lo).cwiseMin(s.up);
    const double ff = f(tt);
    ++s.nv;
    if (ff < s.f) {
      s.t = tt, s.f = ff;
      v = v.cwiseProduct(v);
    } else {
      rept = false;
    }
    if (((tt.array() == s.lo.array()) || (tt.array() == s.up.array())).any()) rept = false;
  }
  rotate_left_pow(s.D, 0.25);
}

}  // namespace

BoxminResult boxmin(const Eigen::VectorXd& theta0, const Eigen::VectorXd& lo, const Eigen::VectorXd& up,
                    const std::function<double(const Eigen::VectorXd&)>& f) {
  const Eigen::Index p = theta0.size();
  if (lo.size() != p || up.size() != p) throw DimensionMismatch("boxmin: theta0, lower and upper differ in length");
  for (Eigen::Index j = 0; j < p; ++j)
    if (!(lo[j] > 0 && lo[j] <= up[j]))
      throw InvalidArgument("boxmin: need 0 < lower <= upper for theta[" + std::to_string(j + 1) + "]");
  State s;
  s.t = theta0, s.lo = lo, s.up = up;
  s.D.resize(p);
  for (Eigen::Index j = 0; j < p; ++j) s.D[j] = std::pow(2.0, static_cast<double>(j + 1) / static_cast<double>(p + 2));
  for (Eigen::Index j = 0; j < p; ++j)
    if (up[j] == lo[j]) s.D[j] = 1, s.t[j] = up[j];
  std::vector<Eigen::Index> ng;  // components started outside the box
  for (Eigen::Index j = 0; j < p; ++j)
    if (s.t[j] < lo[j] || up[j] < s.t[j]) {
      s.t[j] = std::pow(lo[j] * std::pow(up[j], 7.0), 1.0 / 8.0);
      ng.push_back(j);
    }
  for (Eigen::Index j = 0; j < p; ++j)
    if (s.D[j] != 1) s.ne.push_back(j);
  s.f = f(s.t);
  s.nv = 1;
  if (std::isinf(s.f)) return {s.t, s.f, s.nv};

  if (ng.size() > 1) {  // improve the starting guess along each free component
    const double d0 = 16, d1 = 2;
    const Eigen::VectorXd th = s.t;
    const double fth = s.f;
    Eigen::Index jdom = ng[0];
    for (Eigen::Index j : ng) {
      double fk = fth;
      Eigen::VectorXd DD = Eigen::VectorXd::Ones(p);
      for (Eigen::Index g : ng) DD[g] = 1 / d1;
      DD[j] = 1 / d0;
      double alpha = std::numeric_limits<double>::infinity();
      for (Eigen::Index g : ng) alpha = std::min(alpha, std::log(lo[g] / th[g]) / std::log(DD[g]));
      alpha /= 5;
      const Eigen::VectorXd v = DD.array().pow(alpha);
      Eigen::VectorXd tk = th;
      for (int rept = 0; rept < 4; ++rept) {
        const Eigen::VectorXd tt = tk.cwiseProduct(v);
        const double ff = f(tt);
        ++s.nv;
        if (ff <= fk) {
          tk = tt, fk = ff;
          if (ff <= s.f) s.t = tt, s.f = ff, jdom = j;
        } else {
          break;
        }
      }
    }
    if (jdom > 0) std::swap(s.D[0], s.D[jdom]);
  }

  const int kmax = p <= 2 ? 2 : static_cast<int>(std::min<Eigen::Index>(p, 4));
  for (int k = 0; k < kmax; ++k) {
    const Eigen::VectorXd th = s.t;
    explore(s, f);
    move(th, s, f);
  }
  return {s.t, s.f, s.nv};
}

}  // namespace smi::surrogate::kriging
