// SPDX-License-Identifier: MIT
// Speed of the PR / intersection paths, run by run_overlap.sh beside SciPy's
// quad on the same pairs. Prints "key value" lines (seconds per call, best of several runs).
//   - calib_loop_pr: what the calibration objective does per response and evaluation (KDE of
//     2,000 CRN outputs on its 4,001-node grid + the trapezoid of |f_exp − f_pred|); this path
//     is unchanged by the exact overlap and must stay fast.
//   - exact_*: pdf_overlap (crossings + CDF masses) on analytic pairs and on two KDEs.
//   - grid_*: compare_on_grid on a 4,001-node grid that resolves the pdfs (trapezoid + checks).
#include <chrono>
#include <cstdio>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/families.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/pdf_overlap.hpp"
#include "platform/core/rng.hpp"

namespace {
template <class F>
double per_call(int inner, F&& f) {
  double best = 1e300;
  for (int r = 0; r < 5; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < inner; ++i) f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / inner);
  }
  return best;
}
volatile double sink = 0;
}  // namespace

int main() {
  smi::Rng rng(11);
  const Eigen::VectorXd y = (30.0 + 0.4 * rng.normal(2000).array()).matrix();
  const Eigen::VectorXd data = (30.1 + 0.35 * rng.normal(30).array()).matrix();
  const double h = smi::stats::bandwidth_normal_reference(y), hd = smi::stats::bandwidth_normal_reference(data);
  const smi::stats::Grid g = smi::stats::Grid::covering(y, std::max(h, hd), 4001);
  const Eigen::VectorXd fexp = smi::stats::kde_pdf_grid(data, hd, g);
  std::printf("calib_loop_pr %.9f\n", per_call(50, [&] { sink = smi::stats::l1_area_on_grid(fexp, smi::stats::kde_pdf_grid(y, h, g), g); }));
  std::printf("calib_loop_l1_only %.9f\n", per_call(2000, [&] { sink = smi::stats::l1_area_on_grid(fexp, fexp, g); }));

  const smi::stats::Normal n0(0, 1), n1(1, 1), nn(0, 0.01);
  const smi::stats::Gamma g05(0.5, 1), g2(2, 1);
  const smi::stats::Beta b05(0.5, 0.5), b2(2, 2);
  const smi::stats::TruncNormal t6(0, 1, 6, std::numeric_limits<double>::infinity());
  const smi::stats::Normal n7(6.3, 0.3);
  std::printf("exact_normal_normal %.9f\n", per_call(20, [&] { sink = smi::stats::pdf_overlap(n0, n1).l1; }));
  std::printf("exact_normal_narrow %.9f\n", per_call(20, [&] { sink = smi::stats::pdf_overlap(n0, nn).l1; }));
  std::printf("exact_gamma_gamma %.9f\n", per_call(5, [&] { sink = smi::stats::pdf_overlap(g05, g2).l1; }));
  std::printf("exact_beta_beta %.9f\n", per_call(5, [&] { sink = smi::stats::pdf_overlap(b05, b2).l1; }));
  std::printf("exact_truncnormal_normal %.9f\n", per_call(5, [&] { sink = smi::stats::pdf_overlap(t6, n7).l1; }));
  const smi::stats::Kde ky(y, h), kd(data, hd);
  std::printf("exact_kde2000_kde30 %.9f\n", per_call(5, [&] { sink = smi::stats::pdf_overlap(ky, kd).l1; }));
  const smi::stats::Grid gn{-10, 11, 4001};
  std::printf("grid_normal_normal %.9f\n", per_call(50, [&] { sink = smi::stats::compare_on_grid(n0, n1, gn).pr; }));
  std::printf("grid_kde2000_kde30 %.9f\n", per_call(5, [&] { sink = smi::stats::compare_on_grid(ky, kd, g).pr; }));
  return 0;
}
