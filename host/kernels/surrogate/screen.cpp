// SPDX-License-Identifier: MIT
// The PDF-area screening of spec §3 on one CRN base sample, plus Sobol' indices.
#include "kernels/surrogate/screen.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/grid.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/metrics.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"

namespace smi::surrogate::screen {
namespace {

Eigen::MatrixXd run(const propagate::MatrixModel& model, const Eigen::MatrixXd& X, std::size_t q, const char* what) {
  Eigen::MatrixXd Y = model(X);
  if (Y.rows() != X.rows() || Y.cols() != static_cast<Eigen::Index>(q))
    throw DimensionMismatch(std::string("model returned ") + std::to_string(Y.rows()) + " x " + std::to_string(Y.cols()) +
                            " outputs for the " + what + " sample of " + std::to_string(X.rows()) + " rows, expected " +
                            std::to_string(X.rows()) + " x " + std::to_string(q));
  for (Eigen::Index j = 0; j < Y.cols(); ++j)
    for (Eigen::Index i = 0; i < Y.rows(); ++i)
      if (!std::isfinite(Y(i, j)))
        throw InvalidArgument(std::string("model output ") + std::to_string(j + 1) + " is not finite at row " +
                              std::to_string(i + 1) + " of the " + what + " sample");
  return Y;
}

bool spread(const Eigen::VectorXd& y) { return y.maxCoeff() > y.minCoeff(); }

// y with input j fixed at its mean or median (same base sample A: CRN), for each random input.
std::vector<Eigen::MatrixXd> fixed_input_runs(const std::vector<propagate::Input>& inputs, const propagate::MatrixModel& model,
                                              const Eigen::MatrixXd& A, std::size_t q, const Options& opt) {
  std::vector<Eigen::MatrixXd> yfix(inputs.size());
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    if (!inputs[j].dist) continue;
    Eigen::MatrixXd Xj = A;
    const double c = opt.fix == "mean" ? inputs[j].dist->mean() : inputs[j].dist->quantile(0.5);
    Xj.col(static_cast<Eigen::Index>(j)).setConstant(c);
    yfix[j] = run(model, Xj, q, ("fixed '" + inputs[j].name + "'").c_str());
  }
  return yfix;
}

// Sobol': the outputs at a second sample B and at A with column j taken from B (A_B^(j)).
void sobol_runs(const std::vector<propagate::Input>& inputs, const propagate::MatrixModel& model, const Eigen::MatrixXd& A,
                std::size_t q, const Options& opt, Eigen::MatrixXd& yB, std::vector<Eigen::MatrixXd>& yAB) {
  const Eigen::MatrixXd B = propagate::crn_sample(inputs, opt.n, opt.seed, "sobol-B");
  yB = run(model, B, q, "Sobol B");
  yAB.assign(inputs.size(), Eigen::MatrixXd());
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    if (!inputs[j].dist) continue;
    Eigen::MatrixXd Xj = A;
    Xj.col(static_cast<Eigen::Index>(j)) = B.col(static_cast<Eigen::Index>(j));
    yAB[j] = run(model, Xj, q, ("Sobol A_B '" + inputs[j].name + "'").c_str());
  }
}

// The PDF-area index e of each input for output o (y: its base-sample values) and its share ne.
void pdf_area_indices(const std::vector<propagate::Input>& inputs, const Eigen::VectorXd& y,
                      const std::vector<Eigen::MatrixXd>& yfix, std::size_t o, const Options& opt, Result& res) {
  const std::size_t k = inputs.size();
  // Common §0 grid over every sample involved, with the largest bandwidth.
  const double hy = stats::bandwidth_normal_reference(y);
  double h_max = hy, lo = y.minCoeff(), hi = y.maxCoeff();
  std::vector<double> hk(k, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    if (!inputs[j].dist) continue;
    const Eigen::VectorXd yk = yfix[j].col(static_cast<Eigen::Index>(o));
    if (!spread(yk)) continue;
    hk[j] = stats::bandwidth_normal_reference(yk);
    h_max = std::max(h_max, hk[j]), lo = std::min(lo, yk.minCoeff()), hi = std::max(hi, yk.maxCoeff());
  }
  const stats::Grid g = stats::Grid::covering(lo, hi, h_max, opt.grid);
  const Eigen::VectorXd fg = stats::kde_pdf_grid(y, hy, g);
  double total = 0;
  for (std::size_t j = 0; j < k; ++j) {
    Row& r = res.rows[j];
    if (!inputs[j].dist) continue;  // a constant: e = 0
    const Eigen::VectorXd yk = yfix[j].col(static_cast<Eigen::Index>(o));
    if ((yk.array() == y.array()).all())
      r.e = 0;  // CRN: an input the model ignores gives exactly 0
    else if (!spread(yk))
      r.e = 2;  // a point mass against a continuous PDF (spec §3)
    else
      r.e = stats::l1_area_on_grid(stats::kde_pdf_grid(yk, hk[j], g), fg, g);
    total += r.e;
  }
  for (auto& r : res.rows) r.ne = total > 0 ? r.e / total : 0;
}

// Rows sorted by normalised index, largest first, ranked from 1.
void rank_rows(Result& res) {
  std::vector<Row> sorted = res.rows;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Row& a, const Row& b) { return a.ne > b.ne; });
  for (std::size_t i = 0; i < sorted.size(); ++i) sorted[i].rank = static_cast<int>(i + 1);
  res.rows = std::move(sorted);
}

}  // namespace

std::vector<Result> screen(const std::vector<propagate::Input>& inputs, const propagate::MatrixModel& model,
                           const std::vector<std::string>& outputs, const Options& opt) {
  if (opt.n < kMinScreenN) throw InvalidArgument("n must be at least " + std::to_string(kMinScreenN) + ", got " + std::to_string(opt.n));
  if (opt.fix != "mean" && opt.fix != "median")
    throw InvalidArgument("fix must be \"mean\" or \"median\", got '" + opt.fix + "'");
  const std::size_t k = inputs.size();
  const Eigen::MatrixXd A = propagate::crn_sample(inputs, opt.n, opt.seed, "base");
  // Adapters of Lua models learn their output names on the first call: read them after it.
  const Eigen::MatrixXd yA0 = model(A);
  const std::size_t q = outputs.size();
  if (q == 0) throw InvalidArgument("no outputs to screen");
  const Eigen::MatrixXd yA = run([&](const Eigen::MatrixXd&) { return yA0; }, A, q, "base");
  const std::vector<Eigen::MatrixXd> yfix = fixed_input_runs(inputs, model, A, q, opt);
  Eigen::MatrixXd yB;
  std::vector<Eigen::MatrixXd> yAB(k);
  if (opt.sobol) sobol_runs(inputs, model, A, q, opt, yB, yAB);

  std::vector<Result> results(q);
  for (std::size_t o = 0; o < q; ++o) {
    Result& res = results[o];
    res.output = outputs[o];
    const Eigen::VectorXd y = yA.col(static_cast<Eigen::Index>(o));
    res.variance = variance(y);
    res.rows.resize(k);
    for (std::size_t j = 0; j < k; ++j) res.rows[j].input = inputs[j].name;
    if (!spread(y)) {
      res.warnings.push_back("output '" + outputs[o] + "' is constant over the sample: all indices are 0");
    } else {
      pdf_area_indices(inputs, y, yfix, o, opt, res);
      if (opt.sobol) {
        Eigen::MatrixXd fAB(opt.n, static_cast<Eigen::Index>(k));
        for (std::size_t j = 0; j < k; ++j)
          fAB.col(static_cast<Eigen::Index>(j)) = inputs[j].dist ? yAB[j].col(static_cast<Eigen::Index>(o)) : y;
        sobol_indices(y, yB.col(static_cast<Eigen::Index>(o)), fAB, opt.bootstrap, opt.level, opt.seed, res.rows);
      }
    }
    rank_rows(res);
  }
  return results;
}

}  // namespace smi::surrogate::screen
