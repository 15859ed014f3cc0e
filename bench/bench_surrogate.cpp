// SPDX-License-Identifier: MIT
// Kriging and propagation benchmark. Writes the designs and test points it uses to
// DIR (CSV) so that bench/surrogate_peers.py feeds OpenTURNS and scikit-learn the very same
// data, and its own figures to DIR/ours.json. Run through bench/run_surrogate.sh.
//   borehole (8 inputs) and Ishigami (3), N = 50, 200, 1000: fit time, predict 1e6 points
//   (the 10,000 test points repeated 100 times), test RMSE and Q2;
//   propagation: Kriging of a 5-input function on N = 100, 1e6 CRN samples, KDE on 512 points.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/families.hpp"
#include "kernels/stats/grid.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/surrogate/doe.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "kernels/surrogate/propagate.hpp"
#include "platform/core/csv.hpp"
#include "platform/core/json.hpp"
#include "platform/core/number_text.hpp"
#include "platform/core/rng.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double borehole(const Eigen::RowVectorXd& x) {
  const double rw = x[0], r = x[1], Tu = x[2], Hu = x[3], Tl = x[4], Hl = x[5], L = x[6], Kw = x[7];
  const double lr = std::log(r / rw);
  return 2 * M_PI * Tu * (Hu - Hl) / (lr * (1 + 2 * L * Tu / (lr * rw * rw * Kw) + Tu / Tl));
}
double ishigami(const Eigen::RowVectorXd& x) {
  return std::sin(x[0]) + 7 * std::pow(std::sin(x[1]), 2) + 0.1 * std::pow(x[2], 4) * std::sin(x[0]);
}
double five(const Eigen::RowVectorXd& x) {  // smooth 5-input test function for propagation
  return x[0] + 2 * std::sin(x[1]) + x[2] * x[3] + std::exp(0.3 * x[4]);
}

struct Case {
  std::string name;
  Eigen::VectorXd lo, hi;
  double (*f)(const Eigen::RowVectorXd&);
};

Eigen::VectorXd eval(const Case& c, const Eigen::MatrixXd& X) {
  Eigen::VectorXd y(X.rows());
  for (Eigen::Index i = 0; i < X.rows(); ++i) y[i] = c.f(X.row(i));
  return y;
}

// The design (x1..xd) and its outputs (y) through the tree's one CSV codec, with a header row
// (the peers' numpy reads skip it); numbers in the shortest text that reads back exactly.
void write_csv(const std::string& path, const Eigen::MatrixXd& X, const Eigen::VectorXd& y) {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> columns(static_cast<std::size_t>(X.cols() + 1));
  for (Eigen::Index j = 0; j <= X.cols(); ++j) {
    header.push_back(j < X.cols() ? "x" + std::to_string(j + 1) : "y");
    for (Eigen::Index i = 0; i < X.rows(); ++i)
      columns[static_cast<std::size_t>(j)].push_back(smi::number_text(j < X.cols() ? X(i, j) : y[i]));
  }
  std::ofstream(path) << smi::csv::write(header, columns);
}

// One Kriging case: fit on an LHS of each size, predict 10^4 test points (accuracy) and 10^6
// (speed); writes the designs and test set as CSV and one JSON object per size.
void bench_kriging(const Case& c, const std::vector<int>& sizes, const std::string& dir, smi::json::Array& rows) {
  const Eigen::Index d = c.lo.size();
  smi::Rng rng(20200214, smi::hash_label("bench/test/" + c.name));
  const Eigen::MatrixXd Xt = smi::surrogate::doe::scale_to_bounds(rng.uniform_matrix(10000, d), c.lo, c.hi);
  const Eigen::VectorXd yt = eval(c, Xt);
  write_csv(dir + "/" + c.name + "_test.csv", Xt, yt);
  Eigen::MatrixXd Xbig(Xt.rows() * 100, d);
  for (int r = 0; r < 100; ++r) Xbig.middleRows(r * Xt.rows(), Xt.rows()) = Xt;
  for (int N : sizes) {
    const Eigen::MatrixXd X = smi::surrogate::doe::scale_to_bounds(smi::surrogate::doe::lhs(N, d, 7 + N), c.lo, c.hi);
    const Eigen::VectorXd y = eval(c, X);
    write_csv(dir + "/" + c.name + "_" + std::to_string(N) + ".csv", X, y);
    auto t0 = Clock::now();
    const smi::surrogate::kriging::Model m = smi::surrogate::kriging::fit(X, y);
    const double t_fit = since(t0);
    t0 = Clock::now();
    const Eigen::VectorXd yp = smi::surrogate::kriging::predict_mean(m, Xt);
    const double rmse = std::sqrt((yp - yt).squaredNorm() / yt.size());
    const double q2 = 1 - (yp - yt).squaredNorm() / (yt.array() - yt.mean()).square().sum();
    t0 = Clock::now();
    const Eigen::VectorXd ybig = smi::surrogate::kriging::predict_mean(m, Xbig);
    const double t_pred = since(t0);
    std::fprintf(stderr, "%s N=%d fit %.3fs (%d evals) predict1e6 %.3fs rmse %.5g q2 %.5f\n", c.name.c_str(), N,
                 t_fit, m.evaluations, t_pred, rmse, q2);
    rows.push_back(smi::json::Object{{"case", c.name}, {"N", N}, {"fit", t_fit}, {"predict", t_pred}, {"rmse", rmse},
                                     {"q2", q2}, {"evals", m.evaluations}, {"check", ybig[12345]}});
  }
}

// Propagation: 5 standard normal inputs, Kriging on N = 100 LHS points in [-4, 4]^5, 10^6
// samples predicted and their KDE on 512 points (the Auto rule against the exact sum).
smi::json::Value bench_propagation(const std::string& dir) {
  const Case c{"five", Eigen::VectorXd::Constant(5, -4), Eigen::VectorXd::Constant(5, 4), five};
  const Eigen::MatrixXd X = smi::surrogate::doe::scale_to_bounds(smi::surrogate::doe::lhs(100, 5, 11), c.lo, c.hi);
  const Eigen::VectorXd y = eval(c, X);
  write_csv(dir + "/five_100.csv", X, y);
  const smi::surrogate::kriging::Model m = smi::surrogate::kriging::fit(X, y);
  std::vector<smi::surrogate::propagate::Input> in;
  for (int j = 0; j < 5; ++j)
    in.push_back({"x" + std::to_string(j + 1), std::make_shared<smi::stats::Normal>(0.0, 1.0), 0.0});
  auto t0 = Clock::now();
  const Eigen::MatrixXd S = smi::surrogate::propagate::crn_sample(in, 1000000, 1);
  const double t_sample = since(t0);
  const Eigen::VectorXd ys = smi::surrogate::kriging::predict_mean(m, S);
  const double t_predict = since(t0) - t_sample;
  const double h = smi::stats::bandwidth_normal_reference(ys);
  const smi::stats::Grid g = smi::stats::Grid::covering(ys.minCoeff(), ys.maxCoeff(), h, 512);
  // The Auto rule users get from smi.kde: 1e6 x 512 takes the binned path (error bound below).
  const smi::stats::KdeOptions kopt;
  const Eigen::VectorXd pdf = smi::stats::kde_pdf_grid(ys, h, g, kopt);
  const double t_prop = since(t0);
  const double bound = smi::stats::kde_uses_binned(ys.size(), g.n, kopt) ? smi::stats::binned_error_bound(h, smi::stats::kde_bin_width(h, kopt)) : 0.0;
  const double err = (pdf - smi::stats::kde_pdf_grid(ys, h, g)).cwiseAbs().maxCoeff();
  std::fprintf(stderr, "propagation KDE: max |auto - exact| = %.3g (bound %.3g, peak %.4g)\n", err, bound, pdf.maxCoeff());
  std::fprintf(stderr, "propagation 1e6 x 5 + KDE 512: %.3fs = sample %.3f + predict %.3f + kde %.3f (mean %.5f, sd %.5f, pdf mass %.6f)\n",
               t_prop, t_sample, t_predict, t_prop - t_sample - t_predict, ys.mean(),
               std::sqrt((ys.array() - ys.mean()).square().mean()), g.trapezoid(pdf));
  return smi::json::Object{{"time", t_prop}, {"sample", t_sample}, {"predict", t_predict}, {"kde_error", err},
                           {"kde_bound", bound}, {"mean", ys.mean()},
                           {"sd", std::sqrt((ys.array() - ys.mean()).square().mean())}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_surrogate DIR [sizes...]\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::vector<int> sizes = {50, 200, 1000};
  // SMI_BENCH_CASE=borehole|ishigami|none limits the Kriging cases (while iterating).
  const char* only = std::getenv("SMI_BENCH_CASE");
  if (argc > 2) {
    sizes.clear();
    for (int i = 2; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  }
  std::vector<Case> cases = {
      {"borehole",
       (Eigen::VectorXd(8) << 0.05, 100, 63070, 990, 63.1, 700, 1120, 9855).finished(),
       (Eigen::VectorXd(8) << 0.15, 50000, 115600, 1110, 116, 820, 1680, 12045).finished(), borehole},
      {"ishigami", Eigen::VectorXd::Constant(3, -M_PI), Eigen::VectorXd::Constant(3, M_PI), ishigami}};
  smi::json::Array rows;
  for (const Case& c : cases)
    if (!only || c.name == only) bench_kriging(c, sizes, dir, rows);
  const smi::json::Value prop = bench_propagation(dir);
  std::ofstream(dir + "/ours.json") << smi::json::write(smi::json::Object{{"cases", rows}, {"propagation", prop}}, {.indent = 1}) << "\n";
  return 0;
}
