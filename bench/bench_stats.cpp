// SPDX-License-Identifier: MIT
// Speed of the stats kernels, run by run_stats.sh beside SciPy/OpenTURNS/numpy on the
// same data (written here to a folder the peers read). Prints "key value" lines.
//   bench_stats <dir>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/upool.hpp"
#include "platform/core/rng.hpp"

namespace {

template <class F>
double best_of(int reps, F&& f) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f(r);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void write(const std::string& path, const Eigen::VectorXd& v) {
  std::ofstream f(path);
  f.precision(17);
  for (Eigen::Index i = 0; i < v.size(); ++i) f << v[i] << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  // 1. KDE of the 9-point spec data at 1e6 points.
  Eigen::VectorXd x9(9);
  x9 << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  const double h9 = smi::stats::bandwidth_normal_reference(x9);
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(1000000, 28.0, 32.5);
  Eigen::VectorXd p, c;
  std::printf("kde9_pdf_1e6 %.6f\n", best_of(5, [&](int) { p = smi::stats::kde_pdf(x9, h9, y); }));
  std::printf("kde9_cdf_1e6 %.6f\n", best_of(5, [&](int) { c = smi::stats::kde_cdf(x9, h9, y); }));
  std::printf("kde9_checksum %.12f %.12f\n", p.sum() * (y[1] - y[0]), c[500000]);

  // 2. KDE of 1e5 normal points at 1e3 points.
  smi::Rng rng(2024);
  const Eigen::VectorXd big = rng.normal(100000);
  const double hb = smi::stats::bandwidth_normal_reference(big);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(1000, -4.0, 4.0);
  write(dir + "/big.txt", big);
  write(dir + "/q.txt", q);
  Eigen::VectorXd exact, binned;
  std::printf("h_big %.17g\n", hb);
  std::printf("kde1e5_exact %.6f\n", best_of(3, [&](int) { exact = smi::stats::kde_pdf(big, hb, q); }));
  write(dir + "/exact.txt", exact);
  for (double tol : {1e-4, 1e-5, 1e-6}) {
    const double bin = hb * std::sqrt(8.0 * tol);
    const double t = best_of(5, [&](int) { binned = smi::stats::kde_pdf_binned(big, hb, q, bin); });
    std::printf("kde1e5_binned_tol%.0e %.6f maxerr %.3e bound %.3e\n", tol, t, (binned - exact).cwiseAbs().maxCoeff(),
                smi::stats::binned_error_bound(hb, bin));
  }

  // 3. u-pooling threshold, n = 9, 1e6 sets (a fresh seed each repeat: no cache hit).
  double thr = 0;
  std::printf("upool_threshold_n9_1e6 %.6f\n", best_of(5, [&](int r) {
                smi::stats::UpoolMcSettings s;
                s.seed = 1000 + static_cast<std::uint64_t>(r);
                thr = smi::stats::upool_threshold(9, 0.95, s);
              }));
  std::printf("upool_threshold_value %.5f\n", thr);
  std::printf("upool_threshold_cached %.9f\n", best_of(5, [&](int) { thr = smi::stats::upool_threshold(9, 0.95); }));
  return 0;
}
