// SPDX-License-Identifier: MIT
#include "kernels/stats/nelder_mead.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace smi::stats::detail {
namespace {

Eigen::VectorXd run(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x0,
                    const Eigen::VectorXd& step, double ftol, int max_iter) {
  const Eigen::Index d = x0.size();
  std::vector<Eigen::VectorXd> s(d + 1, x0);
  std::vector<double> fv(d + 1);
  for (Eigen::Index i = 0; i < d; ++i) s[i + 1][i] += step[i];
  for (Eigen::Index i = 0; i <= d; ++i) fv[i] = f(s[i]);
  std::vector<Eigen::Index> idx(d + 1);
  for (int it = 0; it < max_iter; ++it) {
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](auto a, auto b) { return fv[a] < fv[b]; });
    const Eigen::Index best = idx[0], worst = idx[d], second = idx[d - 1];
    if (std::abs(fv[worst] - fv[best]) <= ftol * (std::abs(fv[best]) + 1e-300) + 1e-300) break;
    Eigen::VectorXd c = Eigen::VectorXd::Zero(d);
    for (Eigen::Index i = 0; i <= d; ++i)
      if (i != worst) c += s[i];
    c /= static_cast<double>(d);
    const Eigen::VectorXd xr = c + (c - s[worst]);
    const double fr = f(xr);
    if (fr < fv[best]) {
      const Eigen::VectorXd xe = c + 2.0 * (c - s[worst]);
      const double fe = f(xe);
      if (fe < fr) s[worst] = xe, fv[worst] = fe; else s[worst] = xr, fv[worst] = fr;
    } else if (fr < fv[second]) {
      s[worst] = xr, fv[worst] = fr;
    } else {
      const bool outside = fr < fv[worst];
      const Eigen::VectorXd xc = outside ? Eigen::VectorXd(c + 0.5 * (xr - c)) : Eigen::VectorXd(c + 0.5 * (s[worst] - c));
      const double fc = f(xc);
      if (fc < std::min(fr, fv[worst])) {
        s[worst] = xc, fv[worst] = fc;
      } else {
        for (Eigen::Index i = 0; i <= d; ++i)
          if (i != best) s[i] = s[best] + 0.5 * (s[i] - s[best]), fv[i] = f(s[i]);
      }
    }
  }
  const auto b = std::min_element(fv.begin(), fv.end()) - fv.begin();
  return s[static_cast<std::size_t>(b)];
}

}  // namespace

Eigen::VectorXd nelder_mead(const std::function<double(const Eigen::VectorXd&)>& f, Eigen::VectorXd x0,
                            const Eigen::VectorXd& step, double ftol, int max_iter) {
  Eigen::VectorXd x = run(f, x0, step, ftol, max_iter);
  for (int r = 0; r < 3; ++r) x = run(f, x, step * 0.1, ftol, max_iter);
  return x;
}

}  // namespace smi::stats::detail
