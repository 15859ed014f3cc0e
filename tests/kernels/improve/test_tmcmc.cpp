// SPDX-License-Identifier: MIT
// TMCMC (spec §9.2) against the closed-form posterior and evidence of linear-Gaussian models
// (spec §9.3): dimension 2 to 10, prior 0.1x to 100x as wide as the likelihood, the likelihood's
// peak 2.5 prior sds from the prior mean. Tolerances come from the sampler's own error estimate.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

#include "kernels/improve/tmcmc.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

using namespace smi::improve;

namespace {

constexpr double kLog2Pi = 1.8378770664093453;

/// y = A θ + e, e ~ N(0, σ² I), prior N(m0, s0² I): its exact posterior and evidence.
struct LinearGaussian {
  Eigen::MatrixXd A;
  Eigen::VectorXd y, m0;
  double sigma = 1.0, s0 = 1.0;

  LinearGaussian(int d, double width, std::uint64_t seed) {
    smi::Rng rng(seed);
    A = Eigen::MatrixXd::Identity(d, d) + 0.3 * rng.normal_matrix(d, d);
    m0 = rng.normal(d, 1.0, 0.5);
    // The likelihood's sd of θ is about σ/|A|: σ = 1 makes it about 1, the prior `width` times that.
    s0 = width;
    Eigen::VectorXd dir = rng.normal(d);
    dir.normalize();
    const Eigen::VectorXd peak = m0 + 2.5 * s0 * dir;
    y = A * peak;
  }
  Eigen::VectorXd loglik(const Eigen::MatrixXd& T) const {
    const Eigen::MatrixXd R = (T * A.transpose()).rowwise() - y.transpose();
    const double c = -0.5 * static_cast<double>(y.size()) * (kLog2Pi + 2.0 * std::log(sigma));
    return (-0.5 / (sigma * sigma) * R.rowwise().squaredNorm()).array() + c;
  }
  Eigen::MatrixXd post_cov() const {
    const Eigen::Index d = A.cols();
    return (Eigen::MatrixXd::Identity(d, d) / (s0 * s0) + A.transpose() * A / (sigma * sigma)).inverse();
  }
  Eigen::VectorXd post_mean() const { return post_cov() * (m0 / (s0 * s0) + A.transpose() * y / (sigma * sigma)); }
  double log_evidence() const {
    const Eigen::Index n = y.size();
    const Eigen::MatrixXd C = sigma * sigma * Eigen::MatrixXd::Identity(n, n) + s0 * s0 * A * A.transpose();
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    const Eigen::VectorXd r = y - A * m0;
    const Eigen::VectorXd z = llt.matrixL().solve(r);
    const double logdet = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
    return -0.5 * (z.squaredNorm() + logdet + static_cast<double>(n) * kLog2Pi);
  }
  PriorSet prior() const {
    std::vector<Prior> p;
    for (Eigen::Index k = 0; k < m0.size(); ++k) p.push_back({"t" + std::to_string(k), PriorKind::normal, m0[k], s0});
    return PriorSet(p);
  }
};

struct Moments {
  Eigen::VectorXd mean, sd;
};
Moments moments(const Eigen::MatrixXd& X) {
  Moments m;
  m.mean = X.colwise().mean();
  m.sd = ((X.rowwise() - m.mean.transpose()).array().square().colwise().sum() / static_cast<double>(X.rows() - 1)).sqrt();
  return m;
}

}  // namespace

TEST_CASE("TMCMC: linear-Gaussian evidence and posterior against the closed form") {
  struct Case {
    int d;
    double width;
    Eigen::Index samples;
  };
  // The samples make the stated evidence error about 0.02 nats (three of it within 0.05 nats is
  // asked) where the stages are few; the 100x prior needs about 20 stages of tempering.
  const Case cases[] = {{2, 0.1, 4000}, {2, 1.0, 4000}, {2, 100.0, 8000}, {5, 1.0, 6000}, {5, 10.0, 8000}, {10, 0.1, 4000}, {10, 1.0, 8000}, {10, 100.0, 8000}};
  for (const Case& c : cases) {
    const LinearGaussian lg(c.d, c.width, 17 + static_cast<std::uint64_t>(c.d));
    TmcmcOptions o;
    o.samples = c.samples;
    o.seed = 5;
    const TmcmcResult r = tmcmc(lg.prior(), [&](const Eigen::MatrixXd& T) { return lg.loglik(T); }, o);
    INFO("d = " << c.d << ", prior width " << c.width << "x, stages " << r.stages.size() << ", stated error " << r.log_evidence_error
         << ", sweeps in the last stage " << r.stages.back().sweeps << (r.reasons.empty() ? "" : ", " + r.reasons[0]));
    CHECK(r.converged);
    const double exact = lg.log_evidence();
    // About 0.02 nats where the stages are few, 0.06 for the 22 stages of the 10-D 100x prior
    // (whose tolerance is then 3 of it).
    CHECK(r.log_evidence_error < 0.07);
    // The stated error covers the actual one (3 sigma), and the evidence is within 0.05 nats.
    CHECK(std::abs(r.log_evidence - exact) <= std::max(0.05, 3.0 * r.log_evidence_error));
    const Moments m = moments(r.samples);
    const Eigen::VectorXd mu = lg.post_mean(), sd = lg.post_cov().diagonal().cwiseSqrt();
    for (int k = 0; k < c.d; ++k) {
      // 2 % of the posterior sd for the mean (where |mean| is far larger than sd, 2 % of it would
      // say nothing); 2 % for the sd, plus three of the Monte Carlo errors of the equal-weight
      // samples' estimates (sd/√P and sd/√(2P)) for the few effective samples of correlated chains.
      const double n = static_cast<double>(c.samples);
      CHECK(std::abs(m.mean[k] - mu[k]) <= sd[k] * (0.02 + 3.0 / std::sqrt(n)));
      CHECK(std::abs(m.sd[k] / sd[k] - 1.0) <= 0.02 + 3.0 / std::sqrt(2.0 * n));
    }
  }
}

TEST_CASE("TMCMC: the stated evidence error matches the scatter of independent runs") {
  const LinearGaussian lg(3, 10.0, 3);
  TmcmcOptions o;
  o.samples = 500;
  const int runs = 40;
  double sum = 0.0, sum2 = 0.0, stated = 0.0;
  for (int i = 0; i < runs; ++i) {
    o.seed = 100 + static_cast<std::uint64_t>(i);
    const TmcmcResult r = tmcmc(lg.prior(), [&](const Eigen::MatrixXd& T) { return lg.loglik(T); }, o);
    sum += r.log_evidence;
    sum2 += r.log_evidence * r.log_evidence;
    stated += r.log_evidence_error / runs;
  }
  const double mean = sum / runs, sd = std::sqrt((sum2 - runs * mean * mean) / (runs - 1));
  INFO("scatter " << sd << ", stated " << stated << ", mean " << mean << ", exact " << lg.log_evidence());
  CHECK(stated / sd > 0.6);
  CHECK(stated / sd < 1.7);
  // No bias beyond the error of the mean of the runs.
  CHECK(std::abs(mean - lg.log_evidence()) < 3.0 * sd / std::sqrt(runs) + 0.01);
}

TEST_CASE("TMCMC: same seed same numbers, also with the callback on several threads") {
  const LinearGaussian lg(4, 3.0, 9);
  TmcmcOptions o;
  o.samples = 400;
  o.seed = 11;
  const auto f = [&](const Eigen::MatrixXd& T) { return lg.loglik(T); };
  const TmcmcResult a = tmcmc(lg.prior(), f, o);
  o.callback_thread_safe = true;
  o.threads = 3;
  const TmcmcResult b = tmcmc(lg.prior(), f, o);
  CHECK(a.samples == b.samples);
  CHECK(a.log_evidence == b.log_evidence);
  CHECK(a.evaluations == b.evaluations);
  o.seed = 12;
  const TmcmcResult c = tmcmc(lg.prior(), f, o);
  CHECK(c.samples != a.samples);
}

TEST_CASE("TMCMC: uniform and truncated priors count as densities") {
  // One parameter, uniform prior on [0, 4], likelihood N(1; θ, 0.5²): Z = (Φ(6) − Φ(−2)) / 4 ... by
  // symmetry of the Gaussian in θ: Z = (1/4) ∫_0^4 N(θ; 1, 0.5²) dθ.
  std::vector<Prior> p{{"a", PriorKind::uniform, 0, 1, 0.0, 4.0}};
  const auto f = [](const Eigen::MatrixXd& T) {
    return Eigen::VectorXd((-0.5 * ((T.col(0).array() - 1.0) / 0.5).square() - std::log(0.5) - 0.5 * kLog2Pi).matrix());
  };
  TmcmcOptions o;
  o.samples = 4000;
  o.seed = 1;
  const TmcmcResult r = tmcmc(PriorSet(p), f, o);
  const double exact = std::log(0.25 * (0.5 * std::erfc(-6.0 / std::sqrt(2.0)) - 0.5 * std::erfc(2.0 / std::sqrt(2.0))));
  CHECK(std::abs(r.log_evidence - exact) <= std::max(0.02, 3.0 * r.log_evidence_error));
  // A normal prior N(2, 1) truncated to [0, 4]: Z = ∫ N(θ;1,.25) N(θ;2,1) dθ over [0,4] / mass.
  std::vector<Prior> q{{"a", PriorKind::normal, 2.0, 1.0, 0.0, 4.0}};
  const TmcmcResult s = tmcmc(PriorSet(q), f, o);
  // The product of the two normals is N(1; 2, 1.25) times a normal in θ (mean 1.2, var 0.2).
  const double v = 0.2, m = 1.2;
  const double in = 0.5 * (std::erfc(-(4.0 - m) / std::sqrt(2 * v)) - std::erfc(-(0.0 - m) / std::sqrt(2 * v)));
  const double mass = 0.5 * (std::erfc(-2.0 / std::sqrt(2.0)) - std::erfc(2.0 / std::sqrt(2.0)));
  const double exact2 = -0.5 * (1.0 / 1.25) - 0.5 * std::log(2 * M_PI * 1.25) + std::log(in) - std::log(mass);
  CHECK(std::abs(s.log_evidence - exact2) <= std::max(0.02, 3.0 * s.log_evidence_error));
  CHECK(s.samples.minCoeff() >= 0.0);
  CHECK(s.samples.maxCoeff() <= 4.0);
}

TEST_CASE("TMCMC: cancellation stops the sampler") {
  const LinearGaussian lg(2, 1.0, 2);
  smi::cancel::Token token;
  int calls = 0;
  const auto f = [&](const Eigen::MatrixXd& T) {
    if (++calls == 3) token.stop(smi::cancel::Reason::signal, 2);
    return lg.loglik(T);
  };
  TmcmcOptions o;
  o.samples = 200;
  CHECK_THROWS_AS(tmcmc(lg.prior(), f, o, token), smi::Interrupted);
  CHECK(calls == 3);
}

TEST_CASE("TMCMC: bad likelihood values and options are named") {
  std::vector<Prior> p{{"a", PriorKind::uniform, 0, 1, 0.0, 1.0}};
  const auto nan = [](const Eigen::MatrixXd& T) { return Eigen::VectorXd::Constant(T.rows(), std::nan("")); };
  CHECK_THROWS_WITH(tmcmc(PriorSet(p), nan, TmcmcOptions{}), Catch::Contains("returned nan at theta"));
  const auto zero = [](const Eigen::MatrixXd& T) { return Eigen::VectorXd::Constant(T.rows(), -HUGE_VAL); };
  CHECK_THROWS_WITH(tmcmc(PriorSet(p), zero, TmcmcOptions{}), Catch::Contains("zero at every prior draw"));
  CHECK_THROWS_WITH(PriorSet({{"b", PriorKind::uniform}}), Catch::Contains("parameter 'b'"));
  CHECK_THROWS_WITH(PriorSet({{"c", PriorKind::lognormal, -1.0, 1.0}}), Catch::Contains("mean > 0"));
}
