// SPDX-License-Identifier: MIT
#include "kernels/stats/kde_bounded.hpp"

#include <cmath>
#include <fmt/format.h>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/metrics.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::stats {
namespace {

void check_options(const BoundedKdeOptions& o) {
  if (!(o.critical_area > 0.0 && o.critical_area <= 1.0))
    throw InvalidArgument(fmt::format("critical_area must be in (0, 1], got {}", o.critical_area));
  if (o.step < 1) throw InvalidArgument(fmt::format("step must be >= 1, got {}", o.step));
  if (o.compare != "previous" && o.compare != "data")
    throw InvalidArgument(fmt::format("compare must be \"previous\" or \"data\", got \"{}\"", o.compare));
  if (o.grid_nodes < kMinGridNodes)
    throw InvalidArgument(fmt::format("grid_nodes must be >= {}, got {}", kMinGridNodes, o.grid_nodes));
}

void check_data(const Eigen::VectorXd& x) {
  require_size(x, 2, "data");
  require_finite(x, "data");
  if (!(x.maxCoeff() > x.minCoeff()))
    throw InvalidArgument(fmt::format("all {} data values are equal ({}): bounded-data KDE needs spread", x.size(), x[0]));
}

}  // namespace

std::pair<double, double> ebd_bounds(ConstVec x, double alpha, bool unbiased) {
  require_size(x, 2, "data");
  require_finite(x, "data");
  if (!(alpha > 0.0 && alpha < 1.0)) throw InvalidArgument(fmt::format("alpha must be in (0, 1), e.g. 0.1; got {}", alpha));
  const double n = static_cast<double>(x.size());
  double a = x.minCoeff(), b = x.maxCoeff();
  if (!(b > a)) throw InvalidArgument(fmt::format("all {} data values are equal ({}): bounds cannot be estimated", x.size(), a));
  if (unbiased) {
    const double a2 = (n * a - b) / (n - 1.0), b2 = (n * b - a) / (n - 1.0);
    a = a2, b = b2;
  }
  const double c = std::pow(alpha, -1.0 / n), r = b - a;
  return {b - c * r, a + c * r};
}

BoundedKdeResult kde_bounded(const Eigen::VectorXd& x, double lower, double upper, const BoundedKdeOptions& o, int* outside) {
  check_data(x);
  check_options(o);
  if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower < upper))
    throw InvalidArgument(fmt::format("lower ({}) must be < upper ({}), both finite", lower, upper));
  if (outside) *outside = static_cast<int>(((x.array() < lower) || (x.array() > upper)).count());
  const Eigen::Index n = x.size();
  const int m_max = o.max_added < 0 ? static_cast<int>(10 * n) : o.max_added;
  Rng rng(o.seed, hash_label("kde_bd"));

  BoundedKdeResult res;
  res.lower = lower;
  res.upper = upper;
  double h_prev = bandwidth_by_name(x, o.bandwidth);
  Eigen::VectorXd t_prev = x;
  Eigen::VectorXd added(0);
  const Eigen::VectorXd x_only = x;
  const double h_data = h_prev;
  int m = 0;
  Eigen::VectorXd t = x;
  double h = h_prev;
  while (m < m_max) {
    const int k = std::min(o.step, m_max - m);
    m += k;
    if (o.deterministic) {
      added.resize(m);
      for (int j = 0; j < m; ++j) added[j] = lower + (upper - lower) * (j + 0.5) / m;
    } else {
      added.conservativeResize(m);
      for (int j = m - k; j < m; ++j) added[j] = rng.uniform(lower, upper);
    }
    t.resize(n + m);
    t << x, added;
    h = bandwidth_by_name(t, o.bandwidth);
    const bool vs_data = o.compare == "data";
    const Eigen::VectorXd& tref = vs_data ? x_only : t_prev;
    const double href = vs_data ? h_data : h_prev;
    const double hmax = std::max(h, href);
    const Grid g = Grid::covering(std::min(t.minCoeff(), tref.minCoeff()), std::max(t.maxCoeff(), tref.maxCoeff()), hmax,
                                  o.grid_nodes);
    const double ia = intersection_area_on_grid(kde_pdf_grid(tref, href, g, 1), kde_pdf_grid(t, h, g, 1), g);
    res.ia_history.push_back(ia);
    if (ia >= o.critical_area) {
      res.converged = true;
      break;
    }
    t_prev = t;
    h_prev = h;
  }
  res.added = m;
  res.added_points = added;
  KdeOptions ko;
  res.kde = std::make_shared<Kde>(t, h, ko);
  res.kde->set_label("bounded data: " + std::to_string(m) + " added in [" + fmt::format("{:.6g}, {:.6g}", lower, upper) + "]");
  return res;
}

BoundedKdeResult kde_ebd(const Eigen::VectorXd& x, double alpha, bool unbiased, const BoundedKdeOptions& o) {
  check_data(x);
  const auto [l, u] = ebd_bounds(x, alpha, unbiased);
  return kde_bounded(x, l, u, o);
}

}  // namespace smi::stats
