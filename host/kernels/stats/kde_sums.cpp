// SPDX-License-Identifier: MIT
// The Gaussian KDE sums of kde.hpp: exact (windowed over sorted data) and binned.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "kernels/stats/fast_normal.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_uniform_grid.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::stats {
namespace {

// Below this many data points the loop runs over data outside and over a block of x inside
// (long vectorised exp runs); above it, over x outside and the sorted-data window inside.
constexpr Eigen::Index kSmallN = 48;
constexpr Eigen::Index kBlock = 512;

void check_args(ConstVec data, double h) {
  require_size(data, 1, "data");
  if (!(h > 0.0) || !std::isfinite(h)) throw InvalidArgument(fmt::format("bandwidth must be a positive finite number, got {}", h));
}

// Runs f on the data sorted ascending, copying only when they are not sorted already.
template <class F>
void with_sorted(ConstVec data, F&& f) {
  if (std::is_sorted(data.data(), data.data() + data.size())) {
    f(data);
    return;
  }
  Eigen::VectorXd t = data;
  std::sort(t.data(), t.data() + t.size());
  f(ConstVec(t));
}

// Σ_i φ((x − t_i)/h) (unnormalised) at x[b..e) for few data points.
void pdf_small(ConstVec t, double h, ConstVec x, Eigen::VectorXd& out, Eigen::Index b, Eigen::Index e) {
  const double ih = 1.0 / h;
  Eigen::ArrayXd z(kBlock), acc(kBlock);
  for (Eigen::Index s = b; s < e; s += kBlock) {
    const Eigen::Index m = std::min(kBlock, e - s);
    auto xs = x.segment(s, m).array();
    acc.head(m).setZero();
    for (Eigen::Index i = 0; i < t.size(); ++i) {
      z.head(m) = (xs - t[i]) * ih;
      acc.head(m) += (-0.5 * z.head(m).square()).exp();
    }
    out.segment(s, m) = acc.head(m).matrix();
  }
}

void pdf_large(ConstVec t, double h, ConstVec x, Eigen::VectorXd& out, Eigen::Index b, Eigen::Index e) {
  const double ih = 1.0 / h, w = kKdeCutoff * h;
  const double* tb = t.data();
  const double* te = tb + t.size();
  for (Eigen::Index j = b; j < e; ++j) {
    const double xj = x[j];
    const double* lo = std::lower_bound(tb, te, xj - w);
    const double* hi = std::upper_bound(lo, te, xj + w);
    const Eigen::Index m = hi - lo;
    if (m == 0) {
      out[j] = 0.0;
      continue;
    }
    Eigen::Map<const Eigen::ArrayXd> seg(lo, m);
    out[j] = (-0.5 * ((xj - seg) * ih).square()).exp().sum();
  }
}

void cdf_small(ConstVec t, double h, ConstVec x, Eigen::VectorXd& out, Eigen::Index b, Eigen::Index e) {
  const double ih = 1.0 / h;
  const double* tab = detail::phi_table();
  for (Eigen::Index j = b; j < e; ++j) {
    double s = 0.0;
    const double xj = x[j];
    for (Eigen::Index i = 0; i < t.size(); ++i) s += detail::fast_normal_cdf((xj - t[i]) * ih, tab);
    out[j] = s;
  }
}

void cdf_large(ConstVec t, double h, ConstVec x, Eigen::VectorXd& out, Eigen::Index b, Eigen::Index e) {
  const double ih = 1.0 / h, w = 9.0 * h;
  const double* tab = detail::phi_table();
  const double* tb = t.data();
  const double* te = tb + t.size();
  for (Eigen::Index j = b; j < e; ++j) {
    const double xj = x[j];
    const double* lo = std::lower_bound(tb, te, xj - w);  // all before lo count fully
    const double* hi = std::upper_bound(lo, te, xj + w);
    double s = static_cast<double>(lo - tb);
    for (const double* p = lo; p < hi; ++p) s += detail::fast_normal_cdf((xj - *p) * ih, tab);
    out[j] = s;
  }
}

}  // namespace

Eigen::VectorXd kde_pdf(ConstVec data, double h, ConstVec x, int threads) {
  check_args(data, h);
  Eigen::VectorXd out(x.size());
  const auto dx = detail::uniform_spacing(x);
  with_sorted(data, [&](ConstVec t) {
  if (dx && *dx <= h * detail::kUniformPdfMaxStep) {
    detail::uniform_pdf_sums(t, h, x, *dx, out, threads);
    return;
  }
  const double work = static_cast<double>(x.size()) * static_cast<double>(std::min<Eigen::Index>(t.size(), 4000));
  pool::parallel_blocks(x.size(), threads, work, [&](Eigen::Index b, Eigen::Index e) {
    if (t.size() <= kSmallN)
      pdf_small(t, h, x, out, b, e);
    else
      pdf_large(t, h, x, out, b, e);
  });
  });
  out *= kInvSqrt2Pi / (static_cast<double>(data.size()) * h);
  return out;
}

Eigen::VectorXd kde_cdf(ConstVec data, double h, ConstVec x, int threads) {
  check_args(data, h);
  Eigen::VectorXd out(x.size());
  const auto dx = detail::uniform_spacing(x);
  with_sorted(data, [&](ConstVec t) {
  if (dx && *dx <= h / 256.0) {
    detail::uniform_cdf_sums(t, h, x, *dx, out, threads);
    return;
  }
  const double work = static_cast<double>(x.size()) * static_cast<double>(std::min<Eigen::Index>(t.size(), 4000));
  pool::parallel_blocks(x.size(), threads, work, [&](Eigen::Index b, Eigen::Index e) {
    if (t.size() <= kSmallN)
      cdf_small(t, h, x, out, b, e);
    else
      cdf_large(t, h, x, out, b, e);
  });
  });
  out /= static_cast<double>(data.size());
  return out;
}

double binned_error_bound(double h, double bin) { return bin * bin * kInvSqrt2Pi / (8.0 * h * h * h); }

Eigen::VectorXd kde_pdf_binned(ConstVec data, double h, ConstVec x, double bin, int threads) {
  check_args(data, h);
  if (!(bin > 0.0)) throw InvalidArgument(fmt::format("bin width must be > 0, got {}", bin));
  const double lo = data.minCoeff(), hi = data.maxCoeff();
  const Eigen::Index nb = static_cast<Eigen::Index>(std::ceil((hi - lo) / bin)) + 2;
  // Linear binning: each point splits its unit mass between the two nearest bin centres.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(nb);
  const double ib = 1.0 / bin;
  for (Eigen::Index i = 0; i < data.size(); ++i) {
    const double s = (data[i] - lo) * ib;
    const auto k = static_cast<Eigen::Index>(s);
    const double f = s - static_cast<double>(k);
    c[k] += 1.0 - f;
    c[k + 1] += f;
  }
  const double ih = 1.0 / h, w = kKdeCutoff * h;
  Eigen::VectorXd out(x.size());
  pool::parallel_blocks(x.size(), threads, static_cast<double>(x.size()) * (2 * w / bin), [&](Eigen::Index b, Eigen::Index e) {
    Eigen::ArrayXd z;
    for (Eigen::Index j = b; j < e; ++j) {
      const double xj = x[j];
      const auto k0 = std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::ceil((xj - w - lo) * ib)));
      const auto k1 = std::min<Eigen::Index>(nb - 1, static_cast<Eigen::Index>(std::floor((xj + w - lo) * ib)));
      if (k1 < k0) {
        out[j] = 0.0;
        continue;
      }
      const Eigen::Index m = k1 - k0 + 1;
      z = Eigen::ArrayXd::LinSpaced(m, static_cast<double>(k0), static_cast<double>(k1));
      z = (xj - lo - z * bin) * ih;
      out[j] = ((-0.5 * z.square()).exp() * c.segment(k0, m).array()).sum();
    }
  });
  out *= kInvSqrt2Pi / (static_cast<double>(data.size()) * h);
  return out;
}

Eigen::VectorXd kde_pdf_grid(ConstVec data, double h, const Grid& g, int threads) {
  g.validate();
  return kde_pdf(data, h, g.nodes(), threads);
}

}  // namespace smi::stats
