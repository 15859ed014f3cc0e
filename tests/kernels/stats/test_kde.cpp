// SPDX-License-Identifier: MIT
// KDE sums and bandwidth rules against spec §8.1 (independent re-implementation values) and
// closed forms.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_coarse_grid.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/rng.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
Eigen::VectorXd spec_x() {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  return x;
}
Eigen::VectorXd ys() {
  Eigen::VectorXd y(5);
  y << 29.5, 30.0, 30.25, 30.5, 31.0;
  return y;
}
}  // namespace

TEST_CASE("bandwidth rules match spec 8.1") {
  const auto x = spec_x();
  CHECK_THAT(smi::stats::bandwidth_normal_reference(x), WithinAbs(0.2481836818, 1e-10));
  CHECK_THAT(smi::stats::bandwidth_normal_106(x), WithinAbs(0.2483655413, 1e-10));
  CHECK_THAT(smi::stats::bandwidth_robust(x), WithinAbs(0.1861048387, 1e-10));
  CHECK_THAT(smi::stats::bandwidth_scott(x), WithinAbs(0.2343071145, 1e-10));
  CHECK_THAT(smi::stats::bandwidth_mad(x), WithinAbs(0.2529864728, 1e-10));
  CHECK_THAT(smi::stats::bandwidth_by_name(x, "silverman"), WithinAbs(0.2481836818, 1e-10));
  CHECK_THROWS_WITH(smi::stats::bandwidth_by_name(x, "silvermann"), Catch::Contains("unknown bandwidth rule 'silvermann'"));
}

TEST_CASE("bandwidth rules reject degenerate data") {
  Eigen::VectorXd one(1);
  one << 1.0;
  CHECK_THROWS_WITH(smi::stats::bandwidth_normal_reference(one), Catch::Contains("at least 2"));
  CHECK_THROWS_WITH(smi::stats::bandwidth_normal_reference(Eigen::VectorXd::Constant(5, 2.0)), Catch::Contains("all 5 data values are equal"));
  Eigen::VectorXd bad = spec_x();
  bad[3] = std::nan("");
  CHECK_THROWS_WITH(smi::stats::bandwidth_scott(bad), Catch::Contains("data[4] is NaN"));
}

TEST_CASE("LSCV and Sheather-Jones are near the normal reference for a large normal sample") {
  smi::Rng rng(7);
  const Eigen::VectorXd x = rng.normal(1500);
  const double h0 = smi::stats::bandwidth_normal_reference(x);
  CHECK_THAT(smi::stats::bandwidth_sheather_jones(x), WithinRel(h0, 0.15));
  CHECK_THAT(smi::stats::bandwidth_lscv(x), WithinRel(h0, 0.35));
  // Binned pair sums (n > 2000) agree with the exact ones to well under the rules' noise.
  const Eigen::VectorXd big = rng.normal(4000);
  CHECK_THAT(smi::stats::bandwidth_sheather_jones(big), WithinRel(smi::stats::bandwidth_normal_reference(big), 0.15));
}

TEST_CASE("KDE pdf and cdf match spec 8.1") {
  const smi::stats::Kde k(spec_x(), 0.2481836818);
  const Eigen::VectorXd pdf = k.pdf(ys()), cdf = k.cdf(ys());
  const double epdf[] = {0.1947599356, 0.8497143052, 0.8960452764, 0.7055000550, 0.2380421025};
  const double ecdf[] = {0.0274396137, 0.2950008950, 0.5193601822, 0.7227971682, 0.9534190121};
  for (int i = 0; i < 5; ++i) {
    CHECK_THAT(pdf[i], WithinAbs(epdf[i], 1e-10));
    CHECK_THAT(cdf[i], WithinAbs(ecdf[i], 1e-10));
    CHECK_THAT(k.quantile(ecdf[i]), WithinAbs(ys()[i], 1e-8));
  }
  CHECK_THAT(*k.field("bandwidth"), WithinAbs(0.2481836818, 0));
  CHECK_THAT(k.mean(), WithinAbs(30.251111111, 1e-9));
}

TEST_CASE("one-kernel KDE is the normal distribution (closed form)") {
  const smi::stats::Kde k(Eigen::VectorXd::Constant(1, 2.0), 0.5);
  for (double y : {-1.0, 1.3, 2.0, 2.7, 4.9}) {
    CHECK_THAT(k.pdf(y), WithinAbs(smi::normal_pdf((y - 2.0) / 0.5) / 0.5, 1e-15));
    CHECK_THAT(k.cdf(y), WithinAbs(smi::normal_cdf((y - 2.0) / 0.5), 2e-16));
  }
}

TEST_CASE("large-N exact sums, binned path and fast CDF agree with direct summation") {
  smi::Rng rng(3);
  const Eigen::VectorXd t = rng.normal(3000);
  const double h = smi::stats::bandwidth_normal_reference(t);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(101, -5.0, 5.0);
  const Eigen::VectorXd p = smi::stats::kde_pdf(t, h, x), c = smi::stats::kde_cdf(t, h, x);
  const double bin = h * std::sqrt(8.0 * 1e-6);
  const Eigen::VectorXd pb = smi::stats::kde_pdf_binned(t, h, x, bin);
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    double sp = 0, sc = 0;
    for (Eigen::Index i = 0; i < t.size(); ++i) {
      sp += smi::normal_pdf((x[j] - t[i]) / h);
      sc += smi::normal_cdf((x[j] - t[i]) / h);
    }
    sp /= t.size() * h;
    sc /= t.size();
    CHECK_THAT(p[j], WithinAbs(sp, 1e-14));
    CHECK_THAT(c[j], WithinAbs(sc, 1e-14));
    CHECK(std::abs(pb[j] - sp) <= smi::stats::binned_error_bound(h, bin));
  }
  // Threads do not change the numbers.
  CHECK((smi::stats::kde_pdf(t, h, x, 1).array() == smi::stats::kde_pdf(t, h, x, 2).array()).all());
}

TEST_CASE("uniform-grid recurrences agree with direct sums") {
  Eigen::VectorXd x9(9);
  x9 << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  const double h = 0.2481836818;
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(200001, 28.0, 32.5);  // spacing h/1100
  const Eigen::VectorXd p = smi::stats::kde_pdf(x9, h, y), c = smi::stats::kde_cdf(x9, h, y);
  double ep = 0, ec = 0;
  for (Eigen::Index j = 0; j < y.size(); j += 7) {
    double sp = 0, sc = 0;
    for (Eigen::Index i = 0; i < 9; ++i) {
      sp += smi::normal_pdf((y[j] - x9[i]) / h);
      sc += smi::normal_cdf((y[j] - x9[i]) / h);
    }
    ep = std::max(ep, std::abs(p[j] - sp / (9 * h)));
    ec = std::max(ec, std::abs(c[j] - sc / 9));
  }
  CHECK(ep < 1e-12);
  CHECK(ec < 1e-13);
  CHECK((smi::stats::kde_cdf(x9, h, y, 1).array() == smi::stats::kde_cdf(x9, h, y, 2).array()).all());
  // Coarsest spacings that still take the recurrences (h/65 for the pdf, h/257 for the cdf).
  for (double per_h : {65.0, 257.0}) {
    const Eigen::Index m = static_cast<Eigen::Index>(4.5 / (h / per_h)) + 1;
    const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(m, 28.0, 28.0 + (m - 1) * (h / per_h));
    const Eigen::VectorXd gp = smi::stats::kde_pdf(x9, h, g), gc = smi::stats::kde_cdf(x9, h, g);
    for (Eigen::Index j = 0; j < m; j += 3) {
      double sp = 0, sc = 0;
      for (Eigen::Index i = 0; i < 9; ++i) {
        sp += smi::normal_pdf((g[j] - x9[i]) / h);
        sc += smi::normal_cdf((g[j] - x9[i]) / h);
      }
      CHECK(std::abs(gp[j] - sp / (9 * h)) < 1e-12);
      CHECK(std::abs(gc[j] - sc / 9) < 1e-13);
    }
  }
  CHECK((smi::stats::kde_pdf(x9, h, y, 1).array() == smi::stats::kde_pdf(x9, h, y, 2).array()).all());
}

TEST_CASE("uniform-grid pdf recurrences hold up to a spacing of h/4, kernels at every offset from a block") {
  // 400 kernels spread over the whole grid, so that some lie at each end of every 64-node block
  // and at the window's edge (z0 near −(8.9 + 63 δ)), where the chain's factors are largest.
  smi::Rng rng(7);
  Eigen::VectorXd t(400);
  for (Eigen::Index i = 0; i < t.size(); ++i) t[i] = rng.uniform(-3.0, 23.0);
  const double h = 0.37;
  for (double per_h : {4.0, 5.0, 16.0, 63.0, 1.5}) {  // 1.5: too coarse, the direct sums
    const double dx = h / per_h;
    const Eigen::Index m = static_cast<Eigen::Index>(20.0 / dx) + 1;
    const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(m, 0.0, static_cast<double>(m - 1) * dx);
    const Eigen::VectorXd p = smi::stats::kde_pdf(t, h, g, 1);
    double err = 0.0, peak = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      double s = 0.0;
      for (Eigen::Index i = 0; i < t.size(); ++i) s += smi::normal_pdf((g[j] - t[i]) / h);
      s /= static_cast<double>(t.size()) * h;
      err = std::max(err, std::abs(p[j] - s));
      peak = std::max(peak, s);
    }
    INFO("spacing h/" << per_h << ": largest error " << err << " against a peak of " << peak);
    CHECK(err < 1e-13 * peak);
    CHECK((smi::stats::kde_pdf(t, h, g, 2).array() == p.array()).all());
  }
}

TEST_CASE("a KDE on an over-resolved grid: summed on a coarser one and interpolated, within 1e-9 of the peak") {
  smi::Rng rng(19);
  Eigen::VectorXd t(2000);
  for (Eigen::Index i = 0; i < t.size(); ++i) t[i] = rng.normal() * (i % 3 == 0 ? 0.4 : 1.0) + (i % 5 == 0 ? 2.5 : 0.0);
  const double h = smi::stats::bandwidth_normal_reference(t);
  for (double per_h : {20.0, 130.0, 700.0, 5000.0}) {
    const smi::stats::Grid g{-6.0, 9.0, static_cast<Eigen::Index>(15.0 * per_h / h) + 1};
    const auto c = smi::stats::coarse_grid(g, h);
    REQUIRE(c.has_value());
    CHECK(c->coarse.step() <= h * smi::stats::kCoarseKdeStep * (1 + 1e-12));
    CHECK(c->coarse.step() > h * smi::stats::kCoarseKdeStep / 2);
    const Eigen::VectorXd exact = smi::stats::kde_pdf_grid(t, h, g, 1);
    const Eigen::VectorXd fast = smi::stats::kde_pdf_resolved(t, h, g, 2);
    INFO("spacing h/" << per_h << ", ratio " << c->ratio << ": largest error " << (fast - exact).cwiseAbs().maxCoeff()
                      << " of a peak " << exact.maxCoeff());
    CHECK((fast - exact).cwiseAbs().maxCoeff() < 1e-9 * exact.maxCoeff());
    // Exact where a fine node is a coarse one.
    CHECK(std::abs(fast[c->ratio] - exact[c->ratio]) < 1e-14 * exact.maxCoeff());
    // The adjoint is the transpose: <a, I v> = <I' a, v>.
    const Eigen::VectorXd a = rng.uniform(g.n, -1.0, 1.0), v = rng.uniform(c->coarse.n, -1.0, 1.0);
    CHECK(a.dot(smi::stats::interpolate_to_fine(*c, v)) == Approx(smi::stats::interpolate_adjoint(*c, a).dot(v)).epsilon(1e-12));
  }
  // Not coarsened when the grid is not twice finer than h·kCoarseKdeStep (step 1e-3, h/8 < 2e-3).
  CHECK_FALSE(smi::stats::coarse_grid(smi::stats::Grid{0.0, 1.0, 1001}, 0.0159).has_value());
  CHECK(smi::stats::coarse_grid(smi::stats::Grid{0.0, 1.0, 1001}, 0.0161).has_value());
}
