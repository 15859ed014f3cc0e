// SPDX-License-Identifier: MIT
// Sobol' indices from the A, B, A_B^(k) scheme (Saltelli et al. 2010):
//   S_k  = mean(fB (fAB_k - fA)) / V            (Saltelli 2010, first order)
//   ST_k = mean((fA - fAB_k)^2) / (2 V)         (Jansen 1999, total)
// with V the variance of fA and fB pooled. CIs: percentile bootstrap over the rows, the same
// resampled rows for every input.
#include <algorithm>
#include <cmath>

#include "kernels/surrogate/screen.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::surrogate::screen {
namespace {

struct Est {
  Eigen::VectorXd s1, st;
};

Est estimate(const Eigen::VectorXd& fA, const Eigen::VectorXd& fB, const Eigen::MatrixXd& fAB,
             const std::vector<Eigen::Index>* rows) {
  const Eigen::Index n = rows ? static_cast<Eigen::Index>(rows->size()) : fA.size(), k = fAB.cols();
  auto at = [&](Eigen::Index i) { return rows ? (*rows)[i] : i; };
  double sum = 0, sum2 = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = fA[at(i)], b = fB[at(i)];
    sum += a + b, sum2 += a * a + b * b;
  }
  const double mean = sum / (2.0 * n);
  const double V = sum2 / (2.0 * n) - mean * mean;
  Est e{Eigen::VectorXd::Zero(k), Eigen::VectorXd::Zero(k)};
  if (!(V > 0)) return e;
  for (Eigen::Index j = 0; j < k; ++j) {
    double s1 = 0, st = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index r = at(i);
      const double d = fAB(r, j) - fA[r];
      s1 += fB[r] * d, st += d * d;
    }
    e.s1[j] = s1 / n / V, e.st[j] = st / n / (2 * V);
  }
  return e;
}

}  // namespace

void sobol_indices(const Eigen::VectorXd& fA, const Eigen::VectorXd& fB, const Eigen::MatrixXd& fAB, int bootstrap,
                   double level, std::uint64_t seed, std::vector<Row>& rows,
                   const cancel::Token& stop) {
  const Eigen::Index n = fA.size(), k = fAB.cols();
  if (fB.size() != n || fAB.rows() != n || static_cast<Eigen::Index>(rows.size()) < k)
    throw DimensionMismatch("sobol_indices: sizes of fA, fB, fAB and rows disagree");
  if (!(level > 0 && level < 1)) throw InvalidArgument("level must be in (0, 1)");
  const Est e = estimate(fA, fB, fAB, nullptr);
  for (Eigen::Index j = 0; j < k; ++j) {
    rows[j].s1 = e.s1[j], rows[j].st = e.st[j];
    rows[j].s1_lo = rows[j].s1_hi = e.s1[j];
    rows[j].st_lo = rows[j].st_hi = e.st[j];
  }
  if (bootstrap <= 0) return;
  Rng rng(seed, hash_label("smi.screen/bootstrap"));
  Eigen::MatrixXd bs1(bootstrap, k), bst(bootstrap, k);
  std::vector<Eigen::Index> idx(n);
  for (int b = 0; b < bootstrap; ++b) {
    stop.poll();
    for (auto& i : idx) i = rng.integer(0, n - 1);
    const Est eb = estimate(fA, fB, fAB, &idx);
    bs1.row(b) = eb.s1.transpose(), bst.row(b) = eb.st.transpose();
  }
  const double lo = (1 - level) / 2, hi = 1 - lo;
  for (Eigen::Index j = 0; j < k; ++j) {
    rows[j].s1_lo = quantile(bs1.col(j), lo), rows[j].s1_hi = quantile(bs1.col(j), hi);
    rows[j].st_lo = quantile(bst.col(j), lo), rows[j].st_hi = quantile(bst.col(j), hi);
  }
}

}  // namespace smi::surrogate::screen
