// SPDX-License-Identifier: MIT
#pragma once
// Universal Kriging as in DACE (Lophaven, Nielsen & Sondergaard 2002; spec §4): normalised
// inputs and response, polynomial trend by generalised least squares, correlation parameters
// theta either given, found by DACE's `boxmin` pattern search (parity with the paper's
// toolbox), or by maximum likelihood (the default): L-BFGS on the analytic gradient of the
// concentrated likelihood, multistart, bounds scaled to the design.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <iosfwd>
#include <string>
#include <vector>

#include "kernels/surrogate/correlation.hpp"
#include "kernels/surrogate/regression.hpp"
#include "platform/core/defaults.hpp"

namespace smi::surrogate::kriging {

struct FitOptions {
  Trend trend = Trend::constant;
  Corr corr = Corr::gauss;
  /// Given theta (DACE's parametrisation, normalised inputs; length 1 = isotropic): no search.
  std::optional<Eigen::VectorXd> theta;
  /// "ml" (default) or "boxmin" (DACE's pattern search; needs theta0/lower/upper or uses the
  /// DACE manual's 10 / 0.1 / 20).
  std::string method = "ml";
  Eigen::VectorXd theta0, lower, upper;  // length 0 (automatic), 1 or n
  /// Relative nugget added to the correlation diagonal (besides DACE's (10+m) eps), or
  /// estimated by maximum likelihood for noisy responses.
  double nugget = 0.0;
  bool estimate_nugget = false;
  int starts = 0;              // local searches of the ML multistart; 0 = automatic by size
  std::uint64_t seed = 1;      // candidate starting points of the multistart
  bool normalize = true;       // DACE normalisation of inputs and response
  int threads = kDefaultThreads;
};

/// A fitted model: everything prediction needs, in normalised units unless stated.
struct Model {
  Trend trend = Trend::constant;
  Corr corr = Corr::gauss;
  Eigen::VectorXd theta;
  double nugget = 0.0;            // relative, beyond mu = (10 + m) eps
  Eigen::RowVectorXd mS, sS;      // input scalings
  double mY = 0.0, sY = 1.0;      // response scalings
  Eigen::MatrixXd S;              // normalised design (m x n)
  Eigen::VectorXd Y;              // normalised responses
  // Factors at theta (spec §4 steps 1-6).
  Eigen::MatrixXd C;              // lower Cholesky factor of R
  Eigen::MatrixXd Ft, Q, G;       // C^-1 F = Q G (thin QR, G upper p x p)
  Eigen::VectorXd beta, gamma;    // GLS trend coefficients; R^-1 (Y - F beta)
  double sigma2 = 0.0;            // process variance, normalised units (divisor m)
  double psi = 0.0;               // DACE objective sigma2 |R|^(1/m)
  // How theta was found.
  std::string method = "fixed";
  int evaluations = 0;            // objective evaluations of the search
  Eigen::VectorXd lower, upper;   // bounds of the search (empty for fixed theta)
  std::vector<std::string> warnings;

  Eigen::Index size() const { return S.rows(); }
  Eigen::Index inputs() const { return S.cols(); }
  /// sigma^2 in the response's units (DACE's stored sigma2).
  double process_variance() const { return sigma2 * sY * sY; }
};

Model fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const FitOptions& opt = {});

struct Prediction {
  Eigen::VectorXd mean, mse;
};
/// Mean and MSE (with the trend-estimation term) at the rows of X; blocks of points share
/// GEMMs; `threads` workers split the blocks (results do not depend on the split).
Prediction predict(const Model& m, const Eigen::MatrixXd& X, int threads = kDefaultThreads);
/// Mean only: the fast path used by propagation.
Eigen::VectorXd predict_mean(const Model& m, const Eigen::MatrixXd& X, int threads = kDefaultThreads);
/// Gradient of the predicted mean with respect to the inputs at the rows of X (rows x inputs),
/// in closed form (predict_gradient.cpp).
Eigen::MatrixXd predict_gradient(const Model& m, const Eigen::MatrixXd& X, int threads = kDefaultThreads);

/// Closed-form leave-one-out (Dubrule 1983) at the fitted theta: residual y_i - yhat_{-i}.
struct LooResult {
  Eigen::VectorXd residuals, variance;
  double q2 = 0.0, rmse = 0.0;
};
LooResult loo(const Model& m);

/// Names a model file carries beside the numbers: the inputs' names (empty, or one per input)
/// and the output's. They travel with the file so that a loaded surrogate still maps named
/// inputs (smi.propagate, smi.calibrate) to the right columns.
struct ModelNames {
  std::vector<std::string> inputs;
  std::string output;
};

/// Plain-text model file (all numbers with 17 significant digits); load refactorises. Version 2
/// files carry names; version 1 files (no names) still load.
void save(const Model& m, const std::string& path, const ModelNames& names = {});
Model load(const std::string& path, ModelNames* names = nullptr);
/// The same on streams (the sandbox opens the file itself); `path` names it in messages.
void save(const Model& m, std::ostream& os, const std::string& path, const ModelNames& names = {});
Model load(std::istream& is, const std::string& path, ModelNames* names = nullptr);

}  // namespace smi::surrogate::kriging
