// SPDX-License-Identifier: MIT
// The population likelihood (spec §9.1) against its closed form for a linear model with normal
// inputs: y ~ N(A μ, A Σ_x Aᵀ + Σ_ε), the responses of a specimen correlated through the shared
// inputs. The kernel estimate must converge to the joint density, not to a product of marginals.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

#include "kernels/improve/population_likelihood.hpp"
#include "kernels/improve/tmcmc.hpp"
#include "platform/core/errors.hpp"

using namespace smi::improve;

namespace {

constexpr double kLog2Pi = 1.8378770664093453;

double log_normal_density(const Eigen::VectorXd& y, const Eigen::VectorXd& m, const Eigen::MatrixXd& C) {
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  const Eigen::VectorXd z = llt.matrixL().solve(y - m);
  return -0.5 * z.squaredNorm() - llt.matrixL().toDenseMatrix().diagonal().array().log().sum() - 0.5 * static_cast<double>(y.size()) * kLog2Pi;
}

/// Two normal inputs (means calibrated: θ = (μ1, μ2), stds fixed), two responses y = A x.
struct Linear {
  Eigen::Matrix2d A, noise;
  Eigen::Vector2d sd{0.5, 0.3};
  Eigen::MatrixXd data;
  Linear() {
    A << 1.0, 0.2, 1.0, -0.2;  // strongly correlated responses (0.88)
    noise << 0.1 * 0.1, 0.0, 0.0, 0.2 * 0.2;
    data.resize(5, 2);
    data << 1.9, 1.0, 1.2, 1.8, 1.7, 1.5, 1.5, 1.2, 2.0, 1.9;
  }
  std::vector<InputSpec> inputs() const {
    return {InputSpec{.name = "x1", .std = sd[0], .mean_param = 0, .std_param = -1, .shape = {}},
            InputSpec{.name = "x2", .std = sd[1], .mean_param = 1, .std_param = -1, .shape = {}}};
  }
  Model model() const {
    return [A = A](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(X * A.transpose()); };
  }
  Eigen::Matrix2d response_cov() const { return A * sd.array().square().matrix().asDiagonal() * A.transpose() + noise; }
  double exact(const Eigen::Vector2d& mu) const {
    double s = 0.0;
    for (Eigen::Index i = 0; i < data.rows(); ++i) s += log_normal_density(data.row(i).transpose(), A * mu, response_cov());
    return s;
  }
  double marginals(const Eigen::Vector2d& mu) const {
    const Eigen::Matrix2d C = response_cov();
    double s = 0.0;
    for (Eigen::Index i = 0; i < data.rows(); ++i)
      for (int r = 0; r < 2; ++r) {
        const double z = (data(i, r) - (A * mu)[r]) / std::sqrt(C(r, r));
        s += -0.5 * z * z - 0.5 * std::log(C(r, r)) - 0.5 * kLog2Pi;
      }
    return s;
  }
  PopulationLikelihood likelihood(Eigen::Index n, double bandwidth) const {
    PopulationOptions o;
    o.n = n;
    o.seed = 3;
    o.bandwidth = bandwidth;
    return PopulationLikelihood(inputs(), 2, data, noise, model(), o);
  }
};

}  // namespace

TEST_CASE("population likelihood: unbiased without bandwidth, the joint density within its stated error") {
  const Linear lin;
  const PopulationLikelihood like = lin.likelihood(200000, 0.0);
  Eigen::MatrixXd Theta(3, 2);
  Theta << 1.5, 0.5, 1.8, 0.2, 1.2, 0.9;
  const PopulationEstimate e = like.evaluate(Theta);
  for (Eigen::Index t = 0; t < Theta.rows(); ++t) {
    const Eigen::Vector2d mu = Theta.row(t).transpose();
    INFO("theta " << mu.transpose() << ": estimate " << e.loglik[t] << " +- " << e.error[t] << ", exact " << lin.exact(mu) << ", marginals "
                  << lin.marginals(mu));
    CHECK(e.error[t] < 0.05);
    CHECK(std::abs(e.loglik[t] - lin.exact(mu)) < 4.0 * e.error[t]);
    // The product of marginals is a different number: the test tells them apart.
    CHECK(std::abs(lin.marginals(mu) - lin.exact(mu)) > 20.0 * e.error[t]);
  }
  CHECK(like.model_calls() == 1);
  CHECK(like.model_rows() == 3 * 200000);
}

TEST_CASE("population likelihood: with the bandwidth term it converges as N grows") {
  const Linear lin;
  const Eigen::Vector2d mu(1.5, 0.5);
  const Eigen::MatrixXd Theta = mu.transpose();
  double last = HUGE_VAL;
  for (Eigen::Index n : {500, 5000, 50000, 500000}) {
    const PopulationEstimate e = lin.likelihood(n, 1.0).evaluate(Theta);
    const double dev = std::abs(e.loglik[0] - lin.exact(mu));
    INFO("N = " << n << ": deviation " << dev << ", stated error " << e.error[0]);
    CHECK(dev < last + 3.0 * e.error[0]);
    last = dev;
  }
  CHECK(last < 0.05);
}

TEST_CASE("population likelihood: smooth in theta (common random numbers), batches match single rows") {
  const Linear lin;
  const PopulationLikelihood like = lin.likelihood(2000, 1.0);
  Eigen::MatrixXd Theta(2, 2);
  Theta << 1.5, 0.5, 1.5 + 1e-7, 0.5;
  const Eigen::VectorXd ll = like(Theta);
  CHECK(std::abs(ll[1] - ll[0]) < 1e-4);
  const Eigen::MatrixXd one = Theta.topRows(1);
  CHECK(like(one)[0] == ll[0]);
}

TEST_CASE("population likelihood inside TMCMC: the posterior of the means against the closed form") {
  // Flat priors on wide ranges: the posterior of μ is the likelihood normalised; with the closed
  // form it is Gaussian with mean A⁻¹ ȳ and covariance A⁻¹ C A⁻ᵀ / n.
  const Linear lin;
  const PopulationLikelihood like = lin.likelihood(1000, 0.0);
  const PriorSet prior({{"x1.mean", PriorKind::uniform, 0, 1, -2.0, 6.0}, {"x2.mean", PriorKind::uniform, 0, 1, -3.0, 4.0}});
  TmcmcOptions o;
  o.samples = 500;
  o.seed = 2;
  const TmcmcResult r = tmcmc(prior, [&](const Eigen::MatrixXd& T) { return like(T); }, o);
  const Eigen::Vector2d ybar = lin.data.colwise().mean().transpose();
  const Eigen::Vector2d mean = lin.A.inverse() * ybar;
  const Eigen::Matrix2d cov = lin.A.inverse() * lin.response_cov() * lin.A.inverse().transpose() / static_cast<double>(lin.data.rows());
  const Eigen::Vector2d m = r.samples.colwise().mean().transpose();
  for (int k = 0; k < 2; ++k) CHECK(std::abs(m[k] - mean[k]) < 0.25 * std::sqrt(cov(k, k)));
  // Evidence: the Gaussian integral of the exact likelihood over the flat prior (its mass inside the box is ~1).
  const double exact = lin.exact(mean) + 0.5 * std::log(cov.determinant()) + kLog2Pi - std::log(8.0 * 7.0);
  const Eigen::VectorXd err = like.evaluate(r.samples.row(r.map_index)).error;
  CHECK(std::abs(r.log_evidence - exact) < 3.0 * std::hypot(r.log_evidence_error, err[0]) + 0.02);
}

TEST_CASE("population likelihood: bad setups are named") {
  const Linear lin;
  PopulationOptions o;
  Eigen::Matrix2d bad = lin.noise;
  bad(1, 1) = 0.0;
  CHECK_THROWS_WITH(PopulationLikelihood(lin.inputs(), 2, lin.data, bad, lin.model(), o), Catch::Contains("positive definite"));
  Eigen::MatrixXd d = lin.data;
  d(0, 0) = std::nan("");
  CHECK_THROWS_WITH(PopulationLikelihood(lin.inputs(), 2, d, lin.noise, lin.model(), o), Catch::Contains("not finite"));
  const Model nan_model = [](const Eigen::MatrixXd& X) { return Eigen::MatrixXd::Constant(X.rows(), 2, std::nan("")); };
  const PopulationLikelihood l(lin.inputs(), 2, lin.data, lin.noise, nan_model, o);
  CHECK_THROWS_WITH(l(Eigen::MatrixXd::Ones(1, 2)), Catch::Contains("theta = (1, 1)"));
}
